# Bad sweep input: one line naming the flag, exit code 2, before any work (no output file).
. "$(dirname "$0")/lib.inc"

bad_input() {  # bad_input REGEX ARGS...
  local want=$1; shift
  expect_exit 2 "$DB" sweep "$@" --progress none || return
  expect_one_line "$ERR" "$*"
  expect_match "$ERR" "$want" "$*"
  if [ -e "$WORK/x.csv" ]; then bad "output written for bad input: $*"; rm -f "$WORK/x.csv"; fi
  ok
}

SMALL=(--m 0.001 --kappa 0.001 --zeta 1 --max-iter 5)
bad_input '--m: .*empty range' --m 0.01:0.001:0.001 --kappa 0.001 -o "$WORK/x.csv"
bad_input '--kappa: .*step must be > 0' --m 0.001 --kappa 0.001:0.01:0 -o "$WORK/x.csv"
bad_input '--kappa: .*step must be > 0' --m 0.001 --kappa 0.001:0.01:-1 -o "$WORK/x.csv"
bad_input '--m: .*values must be > 0' --m 0:0.01:0.001 --kappa 0.001 -o "$WORK/x.csv"
bad_input '--zeta: .*not a decimal number' --m 0.001 --kappa 0.001 --zeta 0.5,abc -o "$WORK/x.csv"
bad_input '--dt: .*no values|--dt: .*empty' "${SMALL[@]}" --dt '' -o "$WORK/x.csv"
bad_input '--m/--kappa.*more than 4294967295' --m 0.000001:1:0.000001 \
  --kappa 0.000001:1:0.000001 -o "$WORK/x.csv"
bad_input '--m/--kappa.*of memory' --m 0.00001:1:0.00001 --kappa 0.0001:1:0.0001 --zeta 1,2,3,4 \
  -o "$WORK/x.csv"
bad_input '^dampbound: error: -o: ' "${SMALL[@]}" -o /nonexistent-dir/x.csv
bad_input '--map: ' "${SMALL[@]}" -o "$WORK/x.csv" --map /nonexistent-dir/x.png
bad_input '--shard: ' "${SMALL[@]}" -o "$WORK/x.csv" --shard 0/2
bad_input '--shard: ' "${SMALL[@]}" -o "$WORK/x.csv" --shard 3/2
bad_input '--shard: ' "${SMALL[@]}" -o "$WORK/x.csv" --shard two
bad_input '--preset: ' --preset paper-middle -o "$WORK/x.csv"
bad_input '--zeta' "${SMALL[@]}" --gamma 0.001 -o "$WORK/x.csv"

# A journal left by an interrupted run needs --resume (or deleting it).
echo "dampbound-journal v1 sweep=0 1/1 classes=1" >"$WORK/x.csv.journal"
bad_input 'x.csv.journal exists.*--resume' "${SMALL[@]}" -o "$WORK/x.csv"
bad_input 'belongs to another sweep' "${SMALL[@]}" -o "$WORK/x.csv" --resume
rm -f "$WORK/x.csv.journal"

# merge: parts of different sweeps, a missing part.
expect_exit 0 "$DB" sweep "${SMALL[@]}" -o "$WORK/p1.csv" --shard 1/2 --progress none
expect_exit 0 "$DB" sweep --m 0.001 --kappa 0.001 --zeta 0.5 --max-iter 5 -o "$WORK/q2.csv" \
  --shard 2/2 --progress none
expect_exit 2 "$DB" merge "$WORK/p1.csv" "$WORK/q2.csv" -o "$WORK/m.csv"
expect_match "$ERR" 'belongs to sweep' "merge of two sweeps"
expect_exit 2 "$DB" merge "$WORK/p1.csv" -o "$WORK/m.csv"
expect_match "$ERR" 'part 2/2 .* is missing' "merge with a part missing"
expect_one_line "$ERR" "merge error"
[ -e "$WORK/m.csv" ] && bad "merge wrote output on error"
finish
