# Hardening regressions that the battery (tests/battery) cannot express as one bad input:
# journals a kill or a forger left, a disk that fills up mid-sweep, Ctrl-C during a --plain
# trial, the memory of a long run without --trace.
. "$(dirname "$0")/lib.inc"

SMALL=(--m 0.001:0.004:0.001 --kappa 0.001:0.003:0.001 --zeta 0.5,1 --max-iter 50 --progress none)
expect_exit 0 "$DB" sweep "${SMALL[@]}" -o "$WORK/ref.csv"
body() { grep -v '^# scene:' "$1"; }  # the rows and the sweep's identity

# A journal of 0 bytes, or with a torn header (killed between create and header), holds no
# work: --resume starts afresh, and the CSV is the uninterrupted run's.
for torn in "" "dampbound-jour"; do
  printf '%s' "$torn" >"$WORK/t.csv.journal"
  expect_exit 0 "$DB" sweep "${SMALL[@]}" -o "$WORK/t.csv" --resume
  if cmp -s <(body "$WORK/ref.csv") <(body "$WORK/t.csv"); then ok; else bad "resume of a torn journal ('$torn') differs"; fi
  if [ -e "$WORK/t.csv.journal" ]; then bad "journal left after a completed resume"; fi
  rm -f "$WORK/t.csv"
done

# Forged lines with a valid checksum (inf for a restored trial, a negative count) end the
# journal's trusted prefix: those classes run again and the CSV holds no inf or negative count.
journal_line() {  # body -> body + FNV-1a checksum, as core/sweep/journal.cpp writes it
  python3 -c 'import sys
b = sys.argv[1].encode(); h = 2166136261
for c in b: h = ((h ^ c) * 16777619) & 0xffffffff
print("%s %08x" % (sys.argv[1], h))' "$1"
}
id=$(sed -n 's/^# sweep-id: //p' "$WORK/ref.csv")
classes=$(sed -n 's/^# classes: //p' "$WORK/ref.csv")
echo "dampbound-journal v1 sweep=$id 1/1 classes=$classes" >"$WORK/f.csv.journal"
journal_line "0 r 5 inf 0 0 0 0" >>"$WORK/f.csv.journal"
journal_line "1 r 5 0x1p-3 -7 0 0 0" >>"$WORK/f.csv.journal"
expect_exit 0 "$DB" sweep "${SMALL[@]}" -o "$WORK/f.csv" --resume
if cmp -s <(body "$WORK/ref.csv") <(body "$WORK/f.csv"); then ok; else bad "forged journal lines reached the CSV"; fi

# A disk that fills up mid-sweep: exit 2 with one line (not "terminate called ...", 134), the
# journal keeps the finished classes, and --resume finishes once there is space.
FULL="$WORK/full"
mkdir -p "$FULL"
if mount -t tmpfs -o size=256k tmpfs "$FULL" 2>/dev/null; then
  trap 'umount "$FULL" 2>/dev/null; rm -rf "$WORK"' EXIT
  # About 2 s of --plain trials on the paper plane; the disk fills up after 0.3 s, between
  # two syncs of the journal (or, on a slow machine, before the final CSV).
  BIG=(--m 0.001:0.02:0.001 --kappa 0.001:0.005:0.001 --zeta 0.5,1 --max-iter 200 --plain
       --threads 2 --progress none --no-similarity --sync-interval 0)
  expect_exit 0 "$DB" sweep "${BIG[@]}" -o "$WORK/bigref.csv"
  ( sleep 0.3; dd if=/dev/zero of="$FULL/filler" bs=1k 2>/dev/null ) &
  filler=$!
  expect_exit 2 "$DB" sweep "${BIG[@]}" -o "$FULL/x.csv"
  wait "$filler"
  expect_one_line "$ERR" "disk full mid-sweep"
  expect_match "$ERR" 'No space left on device|write failed' "disk full mid-sweep"
  if [ -e "$FULL/x.csv" ]; then bad "a CSV was left on the full disk"; fi
  if ls "$FULL" | grep -q 'tmp'; then bad "a temporary was left on the full disk: $(ls "$FULL")"; fi
  rm -f "$FULL/filler"
  if [ -e "$FULL/x.csv.journal" ]; then
    expect_exit 0 "$DB" sweep "${BIG[@]}" -o "$FULL/x.csv" --resume
    if cmp -s <(body "$WORK/bigref.csv") <(body "$FULL/x.csv"); then ok; else bad "resume after a full disk differs"; fi
  fi
  umount "$FULL"
else
  echo "SKIP: the full-disk case needs root to mount a tmpfs"
fi

# Ctrl-C during a --plain trial of 1e8 iterations stops within a step, not at the trial's end.
"$DB" sweep --m 0.001 --kappa 0.001 --zeta 0 --max-iter 100000000 --plain --threads 1 \
  -o "$WORK/plain.csv" --progress none 2>"$WORK/plain.err" &
pid=$!
sleep 2
t0=$(date +%s%N)
kill -INT "$pid"
wait "$pid"
code=$?
ms=$(( ($(date +%s%N) - t0) / 1000000 ))
if [ "$code" -eq 130 ] && [ "$ms" -lt 5000 ]; then ok; else bad "--plain: exit $code $ms ms after Ctrl-C"; fi

# A long run without --trace keeps no trace: its memory does not grow with the iterations.
cat >"$WORK/osc.toml" <<'TOML'
[[node]]
x = [0, 0, 0]
anchor_scale = 1
[params]
gamma = 0
[[perturb]]
node = 0
displacement = [1, 0, 0]
[protocol]
restore_fraction = 1e-300
TOML
if [ -x /usr/bin/time ]; then
  # Under AddressSanitizer freed memory waits in a quarantine and counts in the RSS: none here.
  rss() { ASAN_OPTIONS="${ASAN_OPTIONS:-}:quarantine_size_mb=0" /usr/bin/time -f %M \
            "$DB" run "$WORK/osc.toml" --max-iter "$1" 2>&1 >/dev/null | tail -n 1; }
  small=$(rss 1000)
  long=$(rss 2000000)
  # A kept trace would be ~200 MB at 2e6 steps (about 100 bytes each); allow 20 MB of noise.
  if [ "$long" -lt $((small + 20000)) ]; then ok; else bad "run without --trace: $long kB against $small kB"; fi
fi

# map: a sweep CSV whose "# scene:" line names a FIFO blocked forever; now the scene is
# refused (a warning: the map is drawn without the exact limit).
mkfifo "$WORK/fifo"
sed 's|^# scene: .*|# scene: '"$WORK"'/fifo|' "$WORK/ref.csv" >"$WORK/fifo-scene.csv"
expect_exit 0 timeout 60 "$DB" map "$WORK/fifo-scene.csv" -o "$WORK/fifo-scene.png"
expect_match "$OUT" 'warning .*fifo: is not a regular file' "map with a FIFO as its scene"

finish
