# Progress on every wait over 2 s (docs/hardening.md, "Interrupting"): bounds and suggest say
# their stage on stderr (DAMPBOUND_PROGRESS_AFTER shortens the 2 s for the test), Ctrl-C ends
# them with one line and exit 130, and a sweep says its rule and what the other would cost.
. "$(dirname "$0")/lib.inc"

export DAMPBOUND_PROGRESS_AFTER=0
# A scene whose analysis takes a moment: the note speaks from its own thread.
expect_exit 0 "$DB" bounds tissue-block-rayleigh --brief
expect_match "$ERR" "^dampbound: bounds: (reading the scene|building the model|exact linear analysis)" "bounds names its stage"
expect_match "$ERR" "^dampbound: bounds: done in [0-9]+ s$" "bounds says when it is done"
expect_exit 0 "$DB" suggest paper-plane --brief
expect_match "$ERR" "^dampbound: suggest: .*\(([0-9]+) of ([0-9]+) done\)" "suggest counts its stages"
expect_exit 0 "$DB" run paper-plane --max-iter 3000
expect_match "$ERR" "^dampbound: run: stepping \(([0-9]+) of 3000 done\)" "run counts its iterations"
unset DAMPBOUND_PROGRESS_AFTER
# Under 2 s nothing is said.
expect_exit 0 "$DB" bounds two-node --brief
[ -z "$ERR" ] && ok || bad "a short bounds printed on stderr: $ERR"

# Ctrl-C during the exact analysis of a mesh: one line naming the stage, exit 130, at once.
DAMPBOUND_PROGRESS_AFTER=0 "$DB" bounds tissue-block >"$WORK/out" 2>"$WORK/err" &
pid=$!
sleep 1.5
t0=$(date +%s%N)
kill -s INT "$pid"
wait "$pid"
rc=$?
ms=$(( ($(date +%s%N) - t0) / 1000000 ))
[ "$rc" -eq 130 ] && ok || bad "Ctrl-C: exit $rc, wanted 130"
[ "$ms" -lt 1000 ] && ok || bad "Ctrl-C took $ms ms"
expect_match "$(tail -1 "$WORK/err")" "^dampbound: bounds: interrupted during .*; nothing was written$" "Ctrl-C says what it stopped"

# A settled sweep says its rule before it starts and, after, what first-entry would have cost.
expect_exit 0 "$DB" sweep two-node --m 0.001 --kappa 0.001,0.002 --zeta 0.5,1 --max-iter 300 \
  --rule settled -o "$WORK/s.csv" --progress lines
expect_match "$ERR" "dampbound: sweep: rule settled: every trial steps to its limit \(300 iterations\)" "the rule, before"
expect_match "$OUT" "^rule +settled: [0-9.e+]+ trial-steps; --rule first-entry would stop each trial at its first entry into the band: [0-9.e+]+ trial-steps \([0-9.]+%" "the other rule's cost"
expect_exit 0 "$DB" sweep two-node --m 0.001 --kappa 0.001,0.002 --zeta 0.5,1 --max-iter 300 \
  --rule first-entry -o "$WORK/f.csv" --progress lines
expect_match "$ERR" "dampbound: sweep: rule first-entry \(the paper's\)" "first-entry named"

finish
