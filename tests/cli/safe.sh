# The safe bound and the safe policy of SPEC 9 through the CLI: bounds, run (text, JSON,
# trace), sweep (the kernel against --plain, the summaries), suggest.
. "$(dirname "$0")/lib.inc"

# The acceptance numbers on the paper plane.
expect_exit 0 "$DB" --digits 5 bounds paper-plane --m 0.001 --kappa 0.001 --dt 0.05
expect_match "$OUT" 'safe bound \(nodal\) +gamma_safe = 0\.039775[0-9]* at node [0-9]+ \(R = 9 1/s\^2\), exact limit 0\.039805[0-9]*, ratio 0\.9992' "gamma_safe"
expect_match "$OUT" 'critical damping +guaranteed at every free node' "critical damping feasible"
expect_match "$OUT" '^safe damping bound +0\.039775 mass unit/s +within' "criteria row"
expect_match "$OUT" '^safe check: critical damping +0 nodes +within' "criteria row: check"
expect_exit 0 "$DB" --digits 5 bounds paper-plane --m 0.001 --kappa 0.001 --dt 0.05 --gamma 0
expect_match "$OUT" 'safe step \(nodal\) +dt_safe = 0\.66667[0-9]* at gamma = 0 \(zeta 0\), node [0-9]+, exact limit 0\.71555[0-9]*, ratio 0\.93168' "dt_safe"
# The middle square damped 3x (gamma_i = 3 gamma there): gamma_safe is the user's gamma, a
# third of the square's gamma_safe_i, just under the exact limit (it was 3x above it).
cat >"$WORK/damped-region.toml" <<'EOF2'
name = "damped-region"
[grid]
nx = 36
nz = 36
spacing = 0.57
diagonals = true
anchors = true
[[region]]
min = [6.8, -1.0, 6.8]
max = [13.7, 1.0, 13.7]
gamma_scale = 3.0
[params]
m = 0.001
kappa = 0.001
gamma = 0.013
dt = 0.05
policy = "fixed"
EOF2
expect_exit 0 "$DB" --digits 5 bounds "$WORK/damped-region.toml"
expect_match "$OUT" "safe bound \(nodal\) +gamma_safe = 0\.013258[0-9]* \(the user's gamma: gamma_i = gamma \* gamma_scale_i\) at node [0-9]+ \(R = 9 1/s\^2\), exact limit 0\.013269[0-9]*, ratio 0\.9992" "gamma_safe in the user's gamma"
expect_match "$OUT" '^safe damping bound +0\.013258[0-9]* mass unit/s +within' "gamma = 0.013: every node within"
expect_exit 0 "$DB" --digits 8 suggest "$WORK/damped-region.toml" --no-verify
expect_match "$OUT" 'safe bound gamma < 0\.013258333 ' "suggest gives the same bound"
# At dt = 0.7 an interior node's gamma_safe_i is negative: suggest says no gamma is
# guaranteed (it printed "gamma < -0.00029285714 guarantees stability at every node").
expect_exit 1 "$DB" --digits 8 suggest paper-plane --dt 0.7 --no-verify  # 1: no damping range at this dt
expect_match "$OUT" 'safe bound no gamma: gamma_safe_i <= 0 at some node at this dt \(-0\.00029285714\)' "suggest: no safe gamma"
# A step too long for critical damping: the nodes are named with the dt that would do.
expect_exit 0 "$DB" --digits 8 bounds paper-plane --dt 0.6
expect_match "$OUT" 'critical damping +NOT guaranteed at [0-9]+ of 1296 nodes .*node [0-9]+ \(dt < 0\.' "infeasible nodes named"
expect_match "$OUT" '^safe check: critical damping +[1-9][0-9]* nodes +BEYOND' "criteria row says beyond"
# Compressed springs: said, not promised.
expect_exit 0 "$DB" --digits 8 bounds two-node --after 3
expect_match "$OUT" 'safe bound \(nodal\)' "two-node safe bound"

# The absurd damping, clamped: fixed diverges, safe settles. Damped at gamma_safe (c dt =
# 1.989, spectral radius 0.9987 per step) the mesh decays slowly: restored after 2000-odd
# iterations, so with the 10000-iteration limit of the paper's upper-bound experiment.
expect_exit 0 "$DB" run paper-plane --gamma 1 --json
expect_match "$OUT" '"outcome":"diverged"' "gamma = 1 as given diverges"
expect_exit 0 "$DB" run paper-plane --policy safe --gamma 1 --max-iter 10000 --json --trace "$WORK/trace.csv"
expect_match "$OUT" '"policy":"safe".*"outcome":"settled"' "safe settles"
expect_match "$OUT" '"unguaranteed":0,"compressed_springs":[0-9]+' "safe counts in the JSON"
expect_exit 0 "$DB" run paper-plane --policy safe --gamma 1 --max-iter 10000 --rule first-entry --json
expect_match "$OUT" '"outcome":"restored","iterations":2[0-9][0-9][0-9],' "safe restores after 2000-odd iterations"
expect_match "$(head -1 "$WORK/trace.csv")" ',safe_bound,unguaranteed,compressed_springs$' "trace columns"
# The watched node is the perturbed one: its springs are stretched, so R is above 9 kappa/m
# and gamma_safe below 0.039775; the policy damps it at exactly its gamma_safe.
row=$(sed -n 2p "$WORK/trace.csv")
column() { head -1 "$WORK/trace.csv" | tr , '\n' | grep -nx "$1" | cut -d: -f1; }
eff=$(column gamma_effective)
safe=$(column safe_bound)
expect_match "$row" '^1,0\.05,' "trace: first row"
[ "$(echo "$row" | cut -d, -f"$eff")" = "$(echo "$row" | cut -d, -f"$safe")" ] && ok ||
  bad "trace: effective gamma is the watched node's gamma_safe: $row"
expect_match "$(echo "$row" | cut -d, -f"$safe")" '^0\.0396' "trace: gamma_safe at the perturbed state"
expect_exit 0 "$DB" run paper-plane --policy safe --gamma 1 --verbose
expect_match "$OUT" 'safe bound +0 node-steps where critical damping was not guaranteed' "run text"

# sweep --policy safe: the batched kernel writes what the plain step() writes.
GRID=(sweep paper-plane --m 0.001,0.004 --kappa 0.001,0.3,0.9 --gamma 0,0.002,1 --max-iter 150
      --policy safe --progress none)
expect_exit 0 "$DB" "${GRID[@]}" -o "$WORK/safe.csv"
expect_match "$OUT" 'safe policy +gamma_safe_i > 0 at every node .*: [0-9]+ trials, [0-9]+ diverged' "safe summary"
expect_exit 0 "$DB" "${GRID[@]}" -o "$WORK/safe-plain.csv" --plain
cmp -s "$WORK/safe.csv" "$WORK/safe-plain.csv" && ok || bad "--plain CSV differs under policy safe"
expect_exit 0 "$DB" sweep paper-plane --m 0.001,0.004 --kappa 0.001,0.3,0.9 --zeta 0.5,1 \
  --max-iter 150 --progress none -o "$WORK/fixed.csv"
expect_match "$OUT" 'divergence +safe check at rest .*says diverges [0-9]+ \(diverged [0-9]+\), says stable [0-9]+ \(diverged 0\)' "safe check as predictor"
expect_match "$OUT" 'divergence +paper runtime check' "paper check as predictor"

# suggest: the safe range per node class and the safe dt.
expect_exit 0 "$DB" --digits 8 suggest paper-plane --no-verify
expect_match "$OUT" 'safe bound gamma < 0\.039775' "suggest: safe gamma"
expect_match "$OUT" 'safe bound: gamma_i in \[0\.002, ' "suggest: per class"
expect_exit 0 "$DB" --digits 8 suggest paper-plane --gamma 0 --no-verify
expect_match "$OUT" 'safe bound dt < 0\.66666667 s' "suggest: safe dt"
# SPEC 9 is derived for the paper's step. Undamped, the two-node system is within every safe
# bound, and forward Euler grows at any dt: the rows give no verdict and say why, and suggest
# promises nothing.
expect_exit 0 "$DB" --digits 8 bounds two-node --gamma 0 --integrator forward-euler
expect_match "$OUT" '^exact spectral radius \(forward-euler\) +[0-9.]+ +BEYOND' "forward Euler undamped grows"
expect_match "$OUT" "^safe damping bound +[0-9.]+ mass unit/s +n/a .*derived for the paper's semi-implicit step, it guarantees nothing under forward-euler$" "safe row: no verdict under forward Euler"
expect_match "$OUT" "^safe dt bound +[0-9.]+ s +n/a " "safe dt row: no verdict under forward Euler"
expect_match "$OUT" '^critical damping +within the safe bound at every free node' "header: not called guaranteed"
expect_exit 0 "$DB" --digits 8 bounds two-node --gamma 0
expect_match "$OUT" '^safe damping bound +[0-9.]+ mass unit/s +within' "the paper's step: judged"
expect_exit 0 "$DB" --digits 8 suggest paper-plane --gamma 0 --integrator verlet --no-verify
expect_match "$OUT" "safe bound dt < 0\.66666667 s \(node [0-9]+ sets it; derived for the paper's semi-implicit step, it guarantees nothing under verlet\)" "suggest: safe dt not promised under Verlet"
finish
