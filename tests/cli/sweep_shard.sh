# --shard K/N runs disjoint parts; merge joins them into exactly the unsplit sweep's CSV.
. "$(dirname "$0")/lib.inc"

GRID=(--m 0.001:0.005:0.001 --kappa 0.001:0.005:0.001 --zeta 0.5,1 --max-iter 80
      --progress none)
expect_exit 0 "$DB" sweep "${GRID[@]}" -o "$WORK/whole.csv"
for k in 1 2 3; do
  expect_exit 0 "$DB" sweep "${GRID[@]}" --shard $k/3 -o "$WORK/part$k.csv"
  expect_match "$OUT" "part $k/3" "part $k"
done
# The parts are disjoint and together hold every trial once.
total=$(cat "$WORK"/part*.csv | grep -v '^#' | grep -vc '^trial')
[ "$total" -eq 50 ] && ok || bad "parts hold $total rows, wanted 50"
dups=$(cat "$WORK"/part*.csv | grep -v '^[#t]' | cut -d, -f1 | sort | uniq -d | wc -l)
[ "$dups" -eq 0 ] && ok || bad "$dups trials in more than one part"
expect_exit 0 "$DB" merge "$WORK/part3.csv" "$WORK/part1.csv" "$WORK/part2.csv" \
  -o "$WORK/merged.csv"
expect_match "$OUT" 'merged +3 parts .*50 trials' "merge report"
cmp -s "$WORK/merged.csv" "$WORK/whole.csv" && ok || bad "merged CSV differs from the whole run"
# A part given twice, or a part of another split, is refused.
expect_exit 2 "$DB" merge "$WORK/part1.csv" "$WORK/part1.csv" "$WORK/part2.csv" -o "$WORK/m2.csv"
expect_match "$ERR" 'also given as' "duplicate part"
finish
