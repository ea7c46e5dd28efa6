# dampbound sweep --rule settled (SPEC 8): three more columns, the same bytes from the batched
# kernel and the plain step(), shards that merge, and first-entry sweeps left as they were.
. "$(dirname "$0")/lib.inc"

GRID=(--m 0.001,0.002 --kappa 0.001,0.002 --zeta 0.25,1 --dt 0.05,0.51 --max-iter 300)
expect_exit 0 "$DB" sweep "${GRID[@]}" --rule settled -o "$WORK/s.csv" --progress none
expect_match "$OUT" 'outcomes +[0-9]+ settled, [0-9]+ not settled \([1-9][0-9]* of them entered the band, then left\), [0-9]+ diverged' \
  "settled outcomes"
expect_match "$OUT" 'overturned +[1-9][0-9]* of [0-9]+ first-entry restores' "overturned count"
expect_match "$(grep '^# definition: ' "$WORK/s.csv")" ' rule=settled$' "definition names the rule"
expect_match "$(grep -v '^#' "$WORK/s.csv" | head -1)" ',zero_length_springs,first_entry,left_at,settled_at$' \
  "settled columns"
awk -F, '!/^#/ && $1 != "trial" && NF != 20 { bad = 1 } END { exit bad }' "$WORK/s.csv" && ok ||
  bad "a settled row without 20 fields"
# settled rows: settled_at > 0 exactly when settled, never before the first entry.
awk -F, '!/^#/ && $1 != "trial" { s = ($11 == "settled"); if (s != ($20 > 0) || (s && $20 < $18)) bad = 1 } END { exit bad }' \
  "$WORK/s.csv" && ok || bad "settled_at inconsistent with the outcome"

# The kernel and the plain step() agree byte for byte under the settled rule too.
expect_exit 0 "$DB" sweep "${GRID[@]}" --rule settled -o "$WORK/p.csv" --plain --progress none
cmp -s "$WORK/s.csv" "$WORK/p.csv" && ok || bad "--plain settled CSV differs from the batched one"

# Settled is the default: a sweep without --rule (and without a preset) is the settled sweep.
expect_exit 0 "$DB" sweep "${GRID[@]}" -o "$WORK/d.csv" --progress none
cmp -s "$WORK/s.csv" "$WORK/d.csv" && ok || bad "a sweep without --rule differs from --rule settled"
# First-entry, asked for, is written as before: 17 columns, no rule in the definition.
expect_exit 0 "$DB" sweep "${GRID[@]}" --rule first-entry -o "$WORK/f.csv" --progress none
expect_match "$(grep -v '^#' "$WORK/f.csv" | head -1)" ',clamped,zero_length_springs$' "first-entry columns"
if grep -q 'rule=' "$WORK/f.csv"; then bad "first-entry definition names a rule"; else ok; fi
# A paper preset names first-entry itself.
expect_exit 0 "$DB" sweep --preset paper-upper --m 0.001 --kappa 0.001 -o "$WORK/preset.csv" --progress none
expect_match "$(grep -v '^#' "$WORK/preset.csv" | head -1)" ',clamped,zero_length_springs$' "a preset sweeps first-entry"
# One run gives both: a restore's iteration is the settled run's first entry.
join -t, <(awk -F, '!/^#/ && $11 == "restored" { print $1 "," $12 }' "$WORK/f.csv" | sort -t, -k1,1) \
  <(awk -F, '!/^#/ && $1 != "trial" { print $1 "," $18 }' "$WORK/s.csv" | sort -t, -k1,1) |
  awk -F, '$2 != $3 { bad = 1 } END { exit bad }' && ok || bad "first entry differs between the rules"

# Shards of a settled sweep merge into the unsplit bytes; a first-entry part does not join them.
for k in 1 2; do
  expect_exit 0 "$DB" sweep "${GRID[@]}" --rule settled --shard "$k/2" -o "$WORK/part$k.csv" --progress none
done
expect_exit 0 "$DB" merge "$WORK/part1.csv" "$WORK/part2.csv" -o "$WORK/merged.csv"
cmp -s "$WORK/s.csv" "$WORK/merged.csv" && ok || bad "merged settled parts differ"
expect_exit 0 "$DB" sweep "${GRID[@]}" --rule first-entry --shard 2/2 -o "$WORK/fpart2.csv" --progress none
expect_exit 2 "$DB" merge "$WORK/part1.csv" "$WORK/fpart2.csv" -o "$WORK/mixed.csv"
expect_match "$ERR" 'belongs to sweep' "first-entry and settled parts are different sweeps"

# A row with the wrong rule's verdict is refused with its file and line.
sed 's/,settled,300,/,restored,300,/' "$WORK/s.csv" >"$WORK/bad.csv"
if "$DB" map --help >/dev/null 2>&1; then
  expect_exit 2 "$DB" map "$WORK/bad.csv" -o "$WORK/bad.png"
  expect_match "$ERR" "bad.csv:[0-9]+: bad outcome 'restored' for rule settled" "wrong verdict named"
  expect_exit 0 "$DB" map "$WORK/s.csv" -o "$WORK/s.png"
  expect_match "$OUT" 'overturned' "map summary counts the overturned verdicts"
fi

finish
