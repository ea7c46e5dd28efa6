# dampbound run under the settled rule (SPEC 8, the default) and the paper's first entry.
. "$(dirname "$0")/lib.inc"

# Past the exact limit (dt 0.51 > 0.504 s): the paper's rule says restored at 12, the
# settled rule sees it leave the band again.
expect_exit 0 "$DB" run paper-plane --dt 0.51 --gamma 0.002 --json
expect_match "$OUT" '"outcome":"not_settled"' "dt 0.51 is not settled"
expect_match "$OUT" '"rule":"settled","first_entry":12,"left_at":[0-9]+,"settled_at":null' \
  "dt 0.51: first entry 12, an exit, no settled iteration"
left=$(printf '%s' "$OUT" | sed -E 's/.*"left_at":([0-9]+).*/\1/')
[ "$left" -gt 12 ] && ok || bad "left_at $left is not after the first entry"
expect_exit 0 "$DB" run paper-plane --dt 0.51 --gamma 0.002 --json --rule first-entry
expect_match "$OUT" '"outcome":"restored","iterations":12,.*"rule":"first-entry","first_entry":12,"left_at":null,"settled_at":null' \
  "--rule first-entry reproduces the paper's restored at 12"

# The text says what happened, in words.
expect_exit 0 "$DB" run paper-plane --dt 0.51 --gamma 0.002
expect_match "$OUT" "answer +(not settled, checked to 1000|diverged at [0-9]+) \(entered the 1% band at 12, left it at $left\)" \
  "text verdict in words"

# Fig. 1 below the lower bound: first entry, exit and settled, settled after the exit.
expect_exit 0 "$DB" run paper-plane --gamma 0.0005 --json
expect_match "$OUT" '"outcome":"settled","iterations":[0-9]+,' "gamma 0.0005 settles by the limit (or SPEC 8's proof)"
fe=$(printf '%s' "$OUT" | sed -E 's/.*"first_entry":([0-9]+).*/\1/')
la=$(printf '%s' "$OUT" | sed -E 's/.*"left_at":([0-9]+).*/\1/')
sa=$(printf '%s' "$OUT" | sed -E 's/.*"settled_at":([0-9]+).*/\1/')
[ "$fe" -lt "$la" ] && [ "$la" -lt "$sa" ] && ok || bad "want first entry < exit < settled: $fe $la $sa"

# The undamped two-node system enters at 31 and never settles.
expect_exit 0 "$DB" run two-node --gamma 0 --json
expect_match "$OUT" '"outcome":"not_settled",.*"first_entry":31,"left_at":[0-9]+,"settled_at":null' \
  "undamped two-node: entered at 31, not settled"

# --trace covers every iteration run (to the limit under the settled rule).
expect_exit 0 "$DB" run two-node --gamma 0 --max-iter 300 --trace "$WORK/a.csv" --json
rows=$(($(wc -l <"$WORK/a.csv") - 1))
[ "$rows" -eq 300 ] && ok || bad "trace has $rows rows, wanted 300"

# Same run twice, same bytes.
"$DB" run paper-plane --gamma 0.0005 --json --trace "$WORK/b1.csv" >"$WORK/j1"
"$DB" run paper-plane --gamma 0.0005 --json --trace "$WORK/b2.csv" >"$WORK/j2"
cmp -s "$WORK/j1" "$WORK/j2" && cmp -s "$WORK/b1.csv" "$WORK/b2.csv" && ok || bad "two runs differ"

# fig1 keeps the paper's rule and says so; a scene's figure is judged by the settled rule
# (headless EGL builds only).
if "$DB" map --help >/dev/null 2>&1; then
  expect_exit 0 "$DB" figure fig1 -o "$WORK/fig1.png"
  expect_match "$OUT" 'gamma = 0\.0005 +restored at 230 \(first entry into the 1% band, the paper.s rule\)' \
    "fig1 names the first-entry rule"
  expect_exit 0 "$DB" figure stiff-region -o "$WORK/stiff.png"
  expect_match "$OUT" 'dt 0\.13 +diverged at 71 \(entered the 1% band at 40, left it at 53\)' \
    "a scene's figure is judged by the settled rule"
fi

# A bad rule: one line naming the flag, exit 2.
expect_exit 2 "$DB" run paper-plane --rule sometimes
expect_one_line "$ERR" "--rule sometimes"
expect_match "$ERR" -- '--rule' "error names --rule"

finish
