# suggest --mass-scale (SPEC 11): the added mass for a target step, its report, the run, the
# cap, the two special answers, --write-scene's round trip, --vtk, --json and bad input.
. "$(dirname "$0")/lib.inc"

# SPEC 11's 8 x 8 plane: node 0 fixed, the 2 x 2 patch (3..4, 3..4) at mass_scale 0.1.
PLANE=$WORK/plane.toml
cat >"$PLANE" <<'TOML'
[grid]
nx = 8
nz = 8
spacing = 0.57
[[region]]
min = [1.7, -1.0, 1.7]
max = [2.3, 1.0, 2.3]
mass_scale = 0.1
[[region]]
min = [0.0, 0.0, 0.0]
max = [0.0, 0.0, 0.0]
fixed = true
[params]
m = 0.001
kappa = 0.001
gamma = 0.002
dt = 0.05
[[perturb]]
node = [4, 4]
displacement = [0.0, 5.0, 0.0]
TOML

expect_exit 0 "$DB" suggest "$PLANE" --mass-scale 0.3
expect_match "$OUT" 'designed for dt_g = 0\.333333 s' "dt_g = dt* / 0.9"
expect_match "$OUT" 'local rule +\+0\.00193[0-9]* \(3\.25% of the free mass 0\.0594\), 4 nodes scaled' "the local rule"
expect_match "$OUT" 'tightened +\+0\.00164[0-9]* \(2\.77%\), s\* = 0\.8516' "the tightened answer"
expect_match "$OUT" 'scaled model exact dt limit 0\.3335[0-9]* s' "the scaled model's limit"
expect_match "$OUT" 'mass 10x below the median' "the cause, in --worst's words"
expect_match "$OUT" 'run at dt\* = 0\.3 s with the scaled masses: verified: settled' "the run"
expect_match "$OUT" '^answer +add 0\.00164[0-9]* \(2\.77% of the free mass\) to 4 nodes' "the answer"
# The same target as a frame and substeps.
expect_exit 0 "$DB" suggest "$PLANE" --frame-dt 0.6 --substeps 2 --no-verify
expect_match "$OUT" 'mass scaling for dt\* = 0\.3 s' "dt* = F / N"
# The scaled scene reads back (run, bounds, suggest), nothing left to add at dt*.
expect_exit 0 "$DB" suggest "$PLANE" --mass-scale 0.3 --no-verify --write-scene "$WORK/scaled.toml" --vtk "$WORK/scaled.vtu"
expect_exit 0 "$DB" suggest "$WORK/scaled.toml" --mass-scale 0.3
expect_match "$OUT" '^answer +nothing to add' "the written scene is stable at dt*"
expect_exit 0 "$DB" run "$WORK/scaled.toml"
expect_match "$OUT" 'settled' "the written scene settles at dt*"
expect_exit 0 "$DB" bounds "$WORK/scaled.toml"
expect_match "$(grep -c 'Name="added_mass"' "$WORK/scaled.vtu")" '^1$' "the .vtu has added_mass"
# JSON for scripts.
expect_exit 0 "$DB" suggest "$PLANE" --mass-scale 0.3 --json --no-verify
expect_match "$OUT" '^\{"scene":.*"answer":"scaled".*"scaled_nodes":4,.*"added_percent":2\.77' "JSON"
# The two special answers and the cap.
expect_exit 0 "$DB" suggest "$PLANE" --mass-scale 0.05
expect_match "$OUT" '^answer +nothing to add: stable at dt_g = 0\.0555556 s as given \(exact dt limit 0\.0878' "nothing to add"
expect_exit 1 "$DB" suggest "$PLANE" --mass-scale 0.2 --rayleigh-mass 10
expect_match "$OUT" '^answer +no mass helps: .* dt\* < 2 f / alpha = 0\.18 s' "no mass helps"
expect_exit 1 "$DB" suggest "$PLANE" --mass-scale 0.3 --kd 0.001 --no-verify
expect_match "$OUT" '^answer +over the cap: 81\.[0-9]% of the free mass > 5%; the largest dt\* within it is' "the cap"
expect_exit 0 "$DB" suggest "$PLANE" --mass-scale 0.3 --kd 0.001 --no-verify --max-added-mass 100
# The shipped scene: three slivers hold the block's step; six nodes take the mass, the lowest
# frequency falls, and its [[expect]] checks of the answer pass.
expect_exit 0 "$DB" suggest tissue-slivers --mass-scale 0.0003
expect_match "$OUT" 'as given +exact dt limit 0\.000203[0-9]* s: unstable' "the slivers' limit"
expect_match "$OUT" 'tightened +\+[0-9.e-]+ \(0\.531%\)' "half a percent"
expect_match "$OUT" 'lowest frequency .*98\.92[0-9]* -> 98\.4[0-9]* 1/s \(-0\.5[0-9]*%\)' "the frequency falls"
expect_match "$OUT" 'spring 50x stiffer than the median' "the slivers' cause"
expect_match "$OUT" '^answer +add [0-9.e-]+ \(0\.531% of the free mass\) to 6 nodes' "six nodes"
expect_exit 0 "$DB" check "$SRC/scenes/tissue-slivers.toml"
# Bad input: one line, exit 2.
for args in "--mass-scale 0.3 --safety 0" "--mass-scale 0.3 --safety 1.5" "--substeps 2" \
            "--write-scene $WORK/x.toml" "--mass-scale 0.3 --integrator rk4" "--mass-scale -1" \
            "--mass-scale 0.3 --max-added-mass -1" "--json"; do
  # shellcheck disable=SC2086
  expect_exit 2 "$DB" suggest "$PLANE" $args && expect_one_line "$ERR" "suggest $args"
done
[ ! -e "$WORK/x.toml" ] && ok || bad "a refused call wrote its scene"
finish
