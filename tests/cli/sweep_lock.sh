# One output, one sweep at a time: while a sweep holds <output>.lock, a second one on the same
# output (resumed or not) is refused with exit 2 and a line that says so, and writes nothing.
. "$(dirname "$0")/lib.inc"

SMALL=(--m 0.001 --kappa 0.001 --zeta 1 --max-iter 5 --progress none)
OUTF=$WORK/locked.csv
exec 9>"$OUTF.lock"  # this shell holds the lock, as a running sweep would
flock -n 9 || bad "could not take the lock"
for extra in "" --resume; do
  expect_exit 2 "$DB" sweep "${SMALL[@]}" -o "$OUTF" $extra || continue
  expect_one_line "$ERR" "second sweep $extra"
  expect_match "$ERR" 'another dampbound sweep is writing .*locked.csv' "second sweep $extra"
  [ -e "$OUTF" ] && bad "the refused sweep wrote $OUTF"
  ok
done
exec 9>&-
# Once the holder is gone the same command runs.
expect_exit 0 "$DB" sweep "${SMALL[@]}" -o "$OUTF" && ok
finish
