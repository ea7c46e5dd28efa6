# dampbound sweep on small grids: one row per trial, each trial once, classes run once, and
# the batched kernel writes exactly the CSV that Session (the plain step()) writes.
. "$(dirname "$0")/lib.inc"

GRID=(--m 0.001:0.004:0.001 --kappa 0.001,0.002,0.004,0.3 --zeta 0.25,1 --max-iter 120)
expect_exit 0 "$DB" sweep "${GRID[@]}" -o "$WORK/a.csv" --progress lines
expect_match "$OUT" 'trials +32 in 2[0-9] classes \(similarity on\)' "trials and classes"
expect_match "$OUT" 'prediction .*held in [0-9]+ of [0-9]+' "prediction summary"
expect_match "$ERR" 'sweep: 100.0% 32/32 trials' "final progress line"
rows=$(grep -vc '^#' "$WORK/a.csv")
[ "$rows" -eq 33 ] && ok || bad "wanted header + 32 rows, got $rows"
# Every trial index exactly once, in order; ran=1 once per class.
awk -F, '!/^#/ && NR > 1 && $1 != "trial" { if ($1 != n) bad = 1; n++ } END { exit bad }' \
  "$WORK/a.csv" && ok || bad "trial indices not 0..31 in order"
classes=$(grep '^# classes: ' "$WORK/a.csv" | cut -d' ' -f3)
ran=$(awk -F, '!/^#/ && $10 == 1' "$WORK/a.csv" | wc -l)
[ "$ran" -eq "$classes" ] && ok || bad "ran=1 rows $ran, classes $classes"
# Rows of one class carry the same results (columns 11-17).
awk -F, '!/^#/ && $1 != "trial" { r = $11 FS $12 FS $13 FS $14 FS $15; if (($9 in s) && s[$9] != r) bad = 1; s[$9] = r } END { exit bad }' \
  "$WORK/a.csv" && ok || bad "a class with different results"

# The plain step() through Session gives the same bytes as the batched kernel.
expect_exit 0 "$DB" sweep "${GRID[@]}" -o "$WORK/plain.csv" --plain --progress none
expect_match "$OUT" 'Session per trial' "plain path used"
cmp -s "$WORK/a.csv" "$WORK/plain.csv" && ok || bad "--plain CSV differs from the batched one"

# Without similarity every trial runs; the trials that ran in both runs agree exactly.
expect_exit 0 "$DB" sweep "${GRID[@]}" -o "$WORK/all.csv" --no-similarity --threads 1 \
  --progress none
expect_match "$OUT" 'trials +32 in 32 classes \(similarity off' "no similarity"
join -t, <(awk -F, '!/^#/ && $10 == 1 { print $1 "," $11 "," $12 "," $13 }' "$WORK/a.csv" |
  sort -t, -k1,1) \
  <(awk -F, '!/^#/ && $1 != "trial" { print $1 "," $11 "," $12 "," $13 }' "$WORK/all.csv" |
  sort -t, -k1,1) |
  awk -F, '$2 != $5 || $3 != $6 || $4 != $7 { bad = 1 } END { exit bad }' && ok ||
  bad "a representative differs between the runs"

# A scene that breaks similarity (external force) falls back to one class per trial.
cat >"$WORK/forced.toml" <<'TOML'
[[node]]
x = [0.0, 0.0, 0.0]
fixed = true
[[node]]
x = [1.0, 0.0, 0.0]
force = [0.0, -0.0001, 0.0]
[[spring]]
nodes = [0, 1]
[[perturb]]
node = 1
displacement = [0.5, 0.0, 0.0]
TOML
expect_exit 0 "$DB" sweep "$WORK/forced.toml" --m 0.001,0.002 --kappa 0.001,0.002 \
  --zeta 1 -o "$WORK/f.csv" --progress none
expect_match "$OUT" 'in 4 classes \(similarity off \(node 1 has an external force\)\)' \
  "fallback with external force"

# Absolute gamma, the two-node scene, every policy.
for p in fixed clamp upper lower safe; do
  expect_exit 0 "$DB" sweep two-node --m 0.001:0.003:0.001 --kappa 0.001:0.003:0.001 \
    --gamma 0:0.004:0.002 --policy $p --factor 1,1.05 -o "$WORK/$p.csv" --progress none
done
finish
