# Resume after a real SIGKILL mid-run (and after Ctrl-C): every trial exactly once, and the
# final CSV byte-identical to an uninterrupted run's.
. "$(dirname "$0")/lib.inc"

# About a second of work on two threads (some 4000 classes of the paper's mesh); the journal
# is synced every 50 ms so that the kill lands in the middle of the run.
GRID=(--m 0.001:0.08:0.001 --kappa 0.001:0.08:0.001 --zeta 1 --max-iter 150 --threads 2
      --sync-interval 0.05 --progress none)

expect_exit 0 "$DB" sweep "${GRID[@]}" -o "$WORK/ref.csv"

# classes_in FILE: the finished classes in a journal (lines after the header, time records
# "t ..." aside).
classes_in() { echo $(($(grep -cv '^t ' "$1") - 1)); }

# wait_for_journal FILE N: until FILE has N finished classes.
wait_for_journal() {
  for _ in $(seq 1 600); do
    [ -f "$1" ] && [ "$(classes_in "$1")" -ge "$2" ] && return 0
    sleep 0.05
  done
  return 1
}

# kill -9 once some classes are journaled.
"$DB" sweep "${GRID[@]}" -o "$WORK/k.csv" >/dev/null 2>&1 &
pid=$!
if wait_for_journal "$WORK/k.csv.journal" 20; then ok; else bad "no journal appeared"; fi
kill -9 $pid 2>/dev/null
wait $pid 2>/dev/null
[ -e "$WORK/k.csv" ] && bad "the sweep finished before the kill: make the grid larger"
[ -e "$WORK/k.csv.journal" ] && ok || bad "journal missing after kill -9"
done_before=$(classes_in "$WORK/k.csv.journal")
# A write torn by the kill: half a line at the end must be detected and dropped.
printf '123 r 45 0x1.8p-5 10' >>"$WORK/k.csv.journal"
expect_exit 0 "$DB" sweep "${GRID[@]}" -o "$WORK/k.csv" --resume
expect_match "$OUT" "classes run now, $done_before from the journal" "resumed classes counted"
# Every synced class has its time record: the killed run's time is known.
expect_match "$OUT" 'in all       [0-9.]+ s \([0-9.]+ s of CPU\) over 2 runs' "time after kill -9"
cmp -s "$WORK/k.csv" "$WORK/ref.csv" && ok || bad "CSV after kill -9 + resume differs"
[ -e "$WORK/k.csv.journal" ] && bad "journal left after a finished sweep"
# --resume on a finished sweep has nothing to do.
expect_exit 0 "$DB" sweep "${GRID[@]}" -o "$WORK/k.csv" --resume
expect_match "$OUT" 'already holds this sweep' "resume of a finished sweep"

# Ctrl-C: the sweep stops, says how to resume, exit 130; --resume finishes it.
"$DB" sweep "${GRID[@]}" -o "$WORK/c.csv" >"$WORK/c.out" 2>"$WORK/c.err" &
pid=$!
wait_for_journal "$WORK/c.csv.journal" 20 || bad "no journal before Ctrl-C"
kill -INT $pid
wait $pid
code=$?
[ "$code" -eq 130 ] && ok || bad "Ctrl-C exit $code, wanted 130"
expect_match "$(cat "$WORK/c.err")" 'interrupted: .*--resume' "Ctrl-C message"
grep -q '^t 1 ' "$WORK/c.csv.journal" && ok || bad "no time record after Ctrl-C"
expect_exit 0 "$DB" sweep "${GRID[@]}" -o "$WORK/c.csv" --resume
cmp -s "$WORK/c.csv" "$WORK/ref.csv" && ok || bad "CSV after Ctrl-C + resume differs"
# The interrupted run recorded its time: the report adds the two runs up.
expect_match "$OUT" 'in all       [0-9.]+ s \([0-9.]+ s of CPU\) over 2 runs' "time over two runs"
finish
