# Every reproducer of a guarantee that once broke (docs/criteria.md, "Dashpots and Rayleigh
# damping"; docs/hardening.md, "The guarantee hunter"), through the command line: what the
# command prints must be what a run or the exact analysis confirms.
. "$(dirname "$0")/lib.inc"
plane="$SRC/scenes/paper-plane.toml"
two="$SRC/scenes/two-node.toml"

# A safe-policy sweep gave one answer to three dampings (the class key ignored gamma under
# `safe`); each row must be what `run` says of the same trial.
expect_exit 0 "$DB" sweep "$plane" --m 0.001 --kappa 0.001 --gamma 0.0005,0.004,0.03 \
  --policy safe --max-iter 300 -o "$WORK/safe.csv" --threads 1
for g in 0.0005 0.004 0.03; do
  row=$(grep -E "^[0-9]+,0\.001,0\.001,$g," "$WORK/safe.csv" | head -1)
  swept=$(printf '%s' "$row" | tr ',' '\n' | grep -Ex 'settled|not_settled|diverged' | head -1)
  "$DB" run "$plane" --policy safe --gamma "$g" --max-iter 300 --json >"$WORK/run.json" 2>/dev/null
  alone=$(grep -Eo '"outcome": *"[a-z_]+"' "$WORK/run.json" | grep -Eo '[a-z_]+"$' | tr -d '"')
  if [ -n "$swept" ] && [ "$swept" = "$alone" ]; then ok; else
    bad "gamma $g: the sweep row says '$swept', run says '$alone' ($row)"; fi
done

# Other integrators with dashpots or Rayleigh damping: the verdict counts the damping (the run
# diverges), and no limit computed without it is printed.
for args in "--integrator forward-euler --kd 0.1" "--integrator rk4 --rayleigh-mass 100" \
            "--integrator verlet --kd 1"; do
  # shellcheck disable=SC2086
  expect_exit 0 "$DB" bounds "$two" $args
  expect_match "$OUT" "exact spectral radius .* BEYOND" "bounds two-node $args: the verdict"
  expect_match "$OUT" "exact dt limit .* n/a +not computed for this damping" \
    "bounds two-node $args: the dt limit"
  # shellcheck disable=SC2086
  "$DB" run "$two" $args --json >"$WORK/run.json" 2>/dev/null
  expect_match "$(cat "$WORK/run.json")" '"outcome": *"diverged"' "run two-node $args"
done

# The damped safe bound with a tiny stiffness: never above the exact limit (0.5 s).
expect_exit 0 "$DB" bounds "$two" --kappa 1e-20 --kd 0.002 --dt 0.6
expect_match "$OUT" "dt_safe = 0\.5 " "the damped safe dt at kappa 1e-20"
expect_exit 0 "$DB" suggest "$two" --kappa 1e-20 --kd 0.002 --frame-dt 0.6 --no-verify
expect_match "$OUT" "safe bound +2 substeps: dt = 0\.3 s < 0\.5 s" "substeps by the damped safe bound"

# suggest quotes the damped safe bound where dashpots act.
expect_exit 0 "$DB" suggest "$SRC/scenes/quad-cloth-dashpots.toml"
expect_match "$OUT" "safe bound gamma < 0\.009625 " "suggest's safe bound with dashpots"

# suggest --gamma exits 1 when the run that checks its answer does not settle: heavily damped,
# the exact limit is the answer (no criterion is stricter) and its one run creeps too slowly.
expect_exit 1 "$DB" suggest "$two" --gamma 0.1
expect_match "$OUT" "NOT verified: not settled" "suggest --gamma 0.1 says its run did not settle"

# Numbers whose intermediates overflow: one line naming the input, exit 2, no verdict.
for args in "--zeta 1e300" "--rayleigh-mass 1e160" "--m 1e-200"; do
  # shellcheck disable=SC2086
  expect_exit 2 "$DB" bounds "$plane" $args && expect_one_line "$ERR" "bounds $args"
  expect_match "$ERR" "out of range|overflows" "bounds $args names what overflows"
  # shellcheck disable=SC2086
  expect_exit 2 "$DB" suggest "$plane" $args
  # shellcheck disable=SC2086
  expect_exit 2 "$DB" run "$plane" $args
done
finish
