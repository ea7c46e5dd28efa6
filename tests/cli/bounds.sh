# dampbound bounds: every criterion side by side (docs/criteria.md).
. "$(dirname "$0")/lib.inc"

# The issue's acceptance command: every criterion, with its value and verdict.
expect_exit 0 "$DB" --digits 8 bounds "$SRC/scenes/paper-plane.toml" --m 0.001 --kappa 0.001 --dt 0.05
for name in 'paper lower bound' 'paper upper bound' 'paper runtime check' 'Delingette critical stiffness' \
  'Provot natural period' 'Kacic-Alesic \(Verlet\) step' 'exact lambda_max of M\^-1 K' \
  'exact spectral radius \(semi-implicit-euler\)' 'exact gamma interval \(semi-implicit-euler\)' \
  'exact dt limit \(semi-implicit-euler\)'; do
  expect_match "$OUT" "^$name +[^ ]+.* (within|BEYOND|n/a) " "bounds lists '$name'"
done
expect_match "$OUT" 'exact lambda_max of M\^-1 K +7\.8123249 1/s\^2' "paper plane lambda_max"
expect_match "$OUT" 'certified in \[7\.8123249[0-9]*, 7\.8123249[0-9]*\]' "lambda_max as a certified interval"
expect_match "$OUT" 'exact gamma interval \(semi-implicit-euler\) +0\.039804692 .*within' "exact gamma interval"
expect_match "$OUT" 'exact dt limit \(semi-implicit-euler\) +0\.50396164 s +within' "exact dt limit"
expect_match "$OUT" 'Delingette critical stiffness +0\.040528473' "Delingette k_c"
expect_match "$OUT" 'Provot natural period +3\.1415927 s +within' "Provot T0"
expect_match "$OUT" 'Kacic-Alesic \(Verlet\) step +0\.75592895 s +within' "Kacic-Alesic"
expect_match "$OUT" 'paper lower bound +0\.002 mass unit/s +within' "eq. 5"
expect_match "$OUT" 'paper upper bound +inf .* n/a +every v_i = 0' "eq. 6 at rest"
expect_match "$OUT" '\[Provot 1995 \(paper ref\. \[2\]\)\]' "sources are printed"

# Beyond the limit the verdicts say so; Kacic-Alesic and Provot still accept (documented).
expect_exit 0 "$DB" --digits 8 bounds paper-plane --gamma 0 --dt 0.73
expect_match "$OUT" 'exact dt limit \(semi-implicit-euler\) +0\.71554977 s +BEYOND' "beyond the exact dt limit"
expect_match "$OUT" 'Kacic-Alesic \(Verlet\) step +0\.75592895 s +within' "Kacic-Alesic accepts an unstable dt"
expect_match "$OUT" 'Delingette critical stiffness .* BEYOND' "Delingette rejects it"

# Parameters only: the paper's lines first (unchanged), then the two-node system, said so.
expect_exit 0 "$DB" --digits 8 bounds --m 0.001 --kappa 0.001 --dt 0.05
expect_match "$OUT" 'gamma_lo = 2\*sqrt\(m\*kappa\) = 0\.002$' "bounds lower line kept"
expect_match "$OUT" 'system +two-node \(paper sec\. 2\)' "says which system"
expect_match "$OUT" 'exact lambda_max of M\^-1 K +1 1/s\^2' "two-node lambda = kappa/m"
expect_match "$OUT" 'exact gamma interval \(semi-implicit-euler\) +0\.039975 ' "2m/dt - kappa dt/2"
expect_match "$OUT" 'gamma=0\.002 \(= gamma_lo\)' "gamma defaults to gamma_lo, said so"
expect_exit 0 "$DB" --digits 8 bounds --m 0.001 --kappa 0.001 --dt 0.05 --gamma 0.01 --system single-node --integrator rk4
expect_match "$OUT" 'system +single node' "single node"
expect_match "$OUT" 'exact dt limit \(rk4\)' "integrator's own limit"
expect_exit 0 "$DB" --digits 8 bounds --m 0.001 --kappa 0.001 --dt 0.05 --v 1,0,0 --force -0.001,0,0
expect_match "$OUT" '= 0\.019' "bounds upper kept"
# Asked about a node's state, it answers that and prints no table of the system at rest
# (whose eq. 6 says inf at v = 0).
if printf '%s\n' "$OUT" | grep -q 'paper upper bound'; then bad "--v/--force printed the at-rest table"; else ok; fi

# Non-uniform scene: the general criterion; a running state: eq. 6 applies.
expect_exit 0 "$DB" --digits 8 bounds stiff-region
expect_match "$OUT" 'exact method symmetric index' "non-uniform method"
expect_match "$OUT" 'paper lower bound +0\.012649111 ' "eq. 5 of the stiff square"
expect_exit 0 "$DB" --digits 8 bounds paper-plane --after 5
expect_match "$OUT" 'state +after 5 steps' "state after 5 steps"
expect_match "$OUT" 'paper upper bound +[0-9.e-]+ mass unit/s +(within|BEYOND) ' "eq. 6 judged while moving"
expect_exit 0 "$DB" --digits 8 bounds stiff-region --integrator implicit-euler
expect_match "$OUT" 'exact dt limit \(implicit-euler\) +inf s +within' "implicit Euler has no limit"

# Over the factorisation budget: the exact rows say "not computed" (no verdict), the safe
# bound (SPEC 9) still judges; the default budget (200 GFlop) changes nothing.
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 1e-9
expect_match "$OUT" '^exact method not computed \(factorisation over budget\)$' "says the exact analysis was skipped"
expect_match "$OUT" 'one factorisation would take [0-9.e-]+ GFlop and [0-9.e-]+ GB, over the budget of 1e-09 GFlop \(--factor-budget\)' "says why"
expect_match "$OUT" 'exact dt limit \(semi-implicit-euler\) +n/a +within +not computed' "no exact value, a verdict from the proofs"
expect_match "$OUT" 'safe dt bound +[0-9.]+ s +within' "the safe bound still judges"
if grep -q 'ratio' <<<"$OUT"; then bad "no ratio to an exact limit that was not computed"; else ok; fi
expect_match "$OUT" 'exact lambda_max of M\^-1 K +n/a +n/a +not computed: .*; without a factorisation \(Lanczos, [0-9]+ steps\): lambda_max in \[7\.8[0-9]*, 9\]' "brackets lambda_max (7.8123249) without a factorisation"
expect_match "$OUT" 'exact dt limit \(semi-implicit-euler\) +n/a +within +not computed: .*every dt >= 0\.50[0-9]+ is unstable at this gamma, every dt <= 0\.48050615 is stable; dt = 0\.05 is stable$' "the dts proved unstable (Lanczos) and stable (Gershgorin, SPEC 9's safe dt 0.48050615)"
expect_match "$OUT" 'exact spectral radius \(semi-implicit-euler\) +n/a +within +not computed: .*<= 0\.2225 \(no spring compressed: K >= 0; Gershgorin on its rows, the safe bound\) < 4: stable \(proved\)$' "the index bounded by Gershgorin: stable (proved)"
# SPEC 10's damping over the budget: no exact index or limits are computed after all (they
# were, unbounded, before the budget reached them), and the answer is what is proved without.
expect_exit 0 "$DB" bounds tissue-block-rayleigh --factor-budget 0.01
expect_match "$OUT" '^exact index +not computed: one factorisation would take .* over the budget of 0\.01 GFlop \(--factor-budget\)' "the damped index is over the budget too"
expect_match "$OUT" 'Rayleigh zeta not computed \(the spectrum is over the factorisation budget\)' "no spectrum, no Rayleigh ratios"
if grep -q '^exact limits ' <<<"$OUT"; then bad "exact limits printed over the budget"; else ok; fi
expect_match "$OUT" '^answer +stable .*\(proved without a factorisation, at rest\)' "the answer from the proofs"
# Between the two proofs (the safe bound 0.039775, the exact limit 0.039805): no verdict.
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 1e-9 --gamma 0.03979
expect_match "$OUT" 'exact gamma interval \(semi-implicit-euler\) +n/a +n/a +not computed: .*every gamma >= 0\.0398[0-9]+ is unstable at this dt, every gamma <= 0\.039775 is stable; gamma = 0\.03979 is not proved either way$' "gamma between the proofs: no verdict"
# Past the exact dt limit (0.50396164), the step is proved unstable without a factorisation.
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 1e-9 --dt 0.51
expect_match "$OUT" 'exact dt limit \(semi-implicit-euler\) +n/a +BEYOND +not computed: .*; dt = 0\.51 is$' "dt past the limit: proved unstable"
expect_match "$OUT" 'exact spectral radius \(semi-implicit-euler\) +n/a +BEYOND +.*>= 4: unstable \(proved\)' "the index proves it"
# Verlet past its dt limit (0.71554977) and forward Euler at too little damping (its gamma_lo
# is 0.00039061625): proved unstable by their per-mode closed forms.
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 1e-9 --integrator verlet --dt 0.72
expect_match "$OUT" 'exact dt limit \(verlet\) +n/a +BEYOND +not computed: .*every dt >= 0\.7155[0-9]+ is unstable at this gamma, every dt <= 0\.66666667 is stable; dt = 0\.72 is$' "Verlet past its dt limit: proved unstable"
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 1e-9 --integrator verlet --dt 0.6
expect_match "$OUT" 'exact dt limit \(verlet\) +n/a +within +not computed: .*every dt <= 0\.66666667 is stable; dt = 0\.6 is stable$' "Verlet within Gershgorin's step: proved stable"
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 1e-9 --integrator forward-euler --gamma 0.00038
expect_match "$OUT" 'exact gamma interval \(forward-euler\) +n/a +BEYOND +not computed: .*every gamma <= 0\.00039[0-9]+ is unstable at this dt, every gamma in \[0\.00045, 0\.04\] is stable; gamma = 0\.00038 is$' "forward Euler under-damped: proved unstable"
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 1e-9 --integrator rk4 --dt 0.99
expect_match "$OUT" 'exact spectral radius \(rk4\) +n/a +BEYOND +not computed: .*every mode with lambda >= 7\.7[0-9]+ is unstable at this gamma and dt; lambda_max >= 7\.8[0-9]+: unstable \(proved\)$' "RK4 past its dt limit (0.98563207): proved unstable"
# RK4 at the scene's dt: every mode in [0, 9] (Gershgorin) is stable, and every gamma and
# every dt up to the limits of modes in [0, 9].
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 1e-9 --integrator rk4
expect_match "$OUT" 'exact spectral radius \(rk4\) +n/a +within +not computed: .*every mode lies in \[0, 9\] .*and each is stable at this gamma and dt: stable \(proved\)$' "RK4 within Gershgorin's bound: proved stable"
expect_match "$OUT" 'exact gamma interval \(rk4\) +n/a +within +not computed: .*every gamma <= 0\.0557[0-9]* is stable; gamma = 0\.002 is stable$' "RK4: every gamma up to the real roots' cap (0.0557058) proved stable"
expect_match "$OUT" 'exact dt limit \(rk4\) +n/a +within +not computed: .*every dt <= 0\.9296[0-9]* is stable; dt = 0\.05 is stable$' "RK4: every dt up to Gershgorin's limit (0.92967) proved stable"
# At dt 0.96 the scene's gamma 0.002 is not proved with every mode in [0, 9]: the gammas that
# are, found from the nearest proved sample rate, leave it out.
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 1e-9 --integrator rk4 --dt 0.96
expect_match "$OUT" 'exact gamma interval \(rk4\) +n/a +n/a +not computed: .*every gamma in \[0\.000169[0-9]*, 0\.00158[0-9]*\] is stable; gamma = 0\.002 is not proved either way$' "RK4: the gammas proved stable though the scene's is not"
# Implicit Euler at rest needs no lambda_max: unconditional, proved without a factorisation.
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 1e-9 --integrator implicit-euler
expect_match "$OUT" 'exact dt limit \(implicit-euler\) +inf s +within +not computed: .*dt_max = inf$' "implicit Euler unconditional over the budget"
expect_exit 0 "$DB" --digits 8 bounds paper-plane --factor-budget 200
expect_match "$OUT" 'exact dt limit \(semi-implicit-euler\) +0\.50396164 s +within' "a budget above the cost changes nothing"
for bad_budget in 0 -1 nan inf x; do
  expect_exit 2 "$DB" --digits 8 bounds paper-plane --factor-budget "$bad_budget"
  expect_one_line "$ERR" "--factor-budget $bad_budget"
  expect_match "$ERR" -- '--factor-budget' "names --factor-budget ($bad_budget)"
done

# A column pushed to 2/3 of its springs' rest length between fixed ends: in equilibrium,
# but K is indefinite there (sideways stiffness 2 kappa (1 - l0/l) < 0) and it buckles. The
# exact rows said "within" (gamma in [0, 0.03995), dt_max 0.73205081) beside rho = 1.021 > 1.
cat >"$WORK/column.toml" <<'EOF2'
name = "column"
watch = 1
[[node]]
x = [0.0, 0.0, 0.0]
fixed = true
[[node]]
x = [0.5, 0.0, 0.0]
[[node]]
x = [1.0, 0.0, 0.0]
fixed = true
[[spring]]
nodes = [0, 1]
rest_length = 0.75
[[spring]]
nodes = [1, 2]
rest_length = 0.75
[params]
m = 0.001
kappa = 0.001
gamma = 0.002
dt = 0.05
policy = "fixed"
[[perturb]]
node = 1
displacement = [0.0, 0.001, 0.0]
EOF2
expect_exit 0 "$DB" --digits 8 bounds "$WORK/column.toml"
expect_match "$OUT" 'lambda_min = -1 ' "column: lambda_min"
expect_match "$OUT" 'exact spectral radius \(semi-implicit-euler\) +1\.0210824 +BEYOND .*K is indefinite' "column: unstable"
expect_match "$OUT" 'exact gamma interval \(semi-implicit-euler\) +0 mass unit/s +BEYOND .*empty interval: K is indefinite' "column: no gamma"
expect_match "$OUT" 'exact dt limit \(semi-implicit-euler\) +0 s +BEYOND +dt = 0\.05: no dt > 0 is stable' "column: no dt"
expect_exit 0 "$DB" run "$WORK/column.toml" --json
expect_match "$OUT" '"outcome":"diverged"' "column: the run buckles"
for integ in forward-euler verlet rk4; do
  expect_exit 0 "$DB" --digits 8 bounds "$WORK/column.toml" --integrator "$integ" --gamma 0.02
  expect_match "$OUT" "exact dt limit \\($integ\\) +0 s +BEYOND" "column: no dt under $integ"
done
expect_exit 0 "$DB" --digits 8 bounds "$WORK/column.toml" --integrator implicit-euler
expect_match "$OUT" 'exact dt limit \(implicit-euler\) +n/a s +n/a +not computed: K is indefinite' "column: implicit Euler's limits not computed"

# A chain of 11 springs between fixed ends, each free node pulled down: not in equilibrium
# at rest (said), and --equilibrium analyses where a damped run settles (the sag's tension
# gives it sideways stiffness: no zero modes there).
{
  echo 'name = "chain"'
  echo 'watch = 6'
  for i in $(seq 0 11); do
    echo '[[node]]'
    echo "x = [$(awk "BEGIN { print 0.5 * $i }"), 0.0, 0.0]"
    if [[ $i == 0 || $i == 11 ]]; then echo 'fixed = true'; else echo 'force = [0.0, -0.0005, 0.0]'; fi
  done
  for i in $(seq 0 10); do
    echo '[[spring]]'
    echo "nodes = [$i, $((i + 1))]"
  done
  echo '[params]'
  echo 'm = 0.001'
  echo 'kappa = 0.001'
  echo 'gamma = 0.002'
  echo 'dt = 0.05'
} >"$WORK/chain.toml"
expect_exit 0 "$DB" --digits 8 bounds "$WORK/chain.toml"
expect_match "$OUT" '^note +the rest state is not an equilibrium: a net force of 0\.0005 at node 1 .*--equilibrium' "chain: the rest state is not an equilibrium"
expect_match "$OUT" 'zero modes, lambda = 0, excluded' "chain at rest: slack, zero modes"
expect_exit 0 "$DB" --digits 8 bounds "$WORK/chain.toml" --equilibrium
expect_match "$OUT" '^state +static equilibrium under the scene.s forces and rest lengths \(v = 0; [0-9]+ Newton steps, net force [0-9.e-]+ against a largest force term of 0\.002521[0-9]*\)' "chain: at the equilibrium"
expect_match "$OUT" 'exact lambda_max of M\^-1 K +3\.7151536 1/s\^2' "chain: lambda_max at the equilibrium (3.9189859 at rest)"
if grep -q 'zero modes' <<<"$OUT" || grep -q '^note' <<<"$OUT"; then bad "chain at equilibrium: zero modes or a note"; else ok; fi
expect_exit 0 "$DB" --digits 8 bounds paper-plane
if grep -q '^note' <<<"$OUT"; then bad "the paper plane at rest is in equilibrium"; else ok; fi
expect_exit 0 "$DB" --digits 8 suggest "$WORK/chain.toml" --no-verify
expect_match "$OUT" '^note +the rest state is not an equilibrium: a net force of 0\.0005 at node 1 .*bounds --equilibrium' "suggest says it too"
expect_exit 0 "$DB" --digits 8 suggest paper-plane --no-verify
if grep -q '^note' <<<"$OUT"; then bad "suggest: the paper plane at rest is in equilibrium"; else ok; fi
expect_exit 2 "$DB" --digits 8 bounds "$WORK/chain.toml" --equilibrium --after 3
expect_one_line "$ERR" "--equilibrium with --after"
expect_exit 3 "$DB" --digits 8 bounds "$WORK/chain.toml" --equilibrium --factor-budget 1e-12
expect_one_line "$ERR" "--equilibrium over the budget"

# Bad input: one line, exit 2.
expect_exit 2 "$DB" --digits 8 bounds --m 0.001 --kappa 0.001
expect_one_line "$ERR" "missing --dt"
expect_match "$ERR" -- '--dt' "names --dt"
expect_exit 2 "$DB" --digits 8 bounds paper-plane --v 1,0,0 --force 0,0,0
expect_one_line "$ERR" "--v with a scene"
expect_exit 2 "$DB" --digits 8 bounds paper-plane --integrator leapfrog
expect_match "$ERR" -- '--integrator' "names --integrator"
expect_exit 2 "$DB" --digits 8 bounds "$WORK/missing.toml"

finish
