# suggest --kappa-max, suggest --rayleigh, diff and [[expect]] limits: answers against closed
# forms, a pair of meshes where one small element halves the step (exit 1, the element named),
# baselines, JUnit, and bad input (exit 2, one line).
. "$(dirname "$0")/lib.inc"

# A 6 x 6 triangle mesh (density and young: lumped masses, edge stiffness from the cells); NEW
# adds one small triangle below the edge z = 0, its vertex first (every other node renumbered).
/usr/bin/python3 - "$WORK" <<'PY'
import sys
work = sys.argv[1]
def write(name, extra):
    vs, idx = [], {}
    if extra:
        vs.append((2.5, 0, -0.3))
    for a in range(6):
        for b in range(6):
            idx[(a, b)] = len(vs) + 1
            vs.append((a, 0, b))
    fs = []
    for a in range(5):
        for b in range(5):
            p, q, r, s = idx[(a, b)], idx[(a + 1, b)], idx[(a + 1, b + 1)], idx[(a, b + 1)]
            fs += [(p, q, r), (p, r, s)]
    if extra:
        fs.append((idx[(2, 0)], 1, idx[(3, 0)]))
    with open(f"{work}/{name}.obj", "w") as f:
        f.writelines("v %g %g %g\n" % v for v in vs)
        f.writelines("f %d %d %d\n" % t for t in fs)
    with open(f"{work}/{name}.toml", "w") as f:
        f.write(f'name = "{name}"\n[mesh]\nfile = "{name}.obj"\ndensity = 1.0\nyoung = 1.0\n'
                '[params]\nm = 1.0\nkappa = 1.0\ngamma = 0.05\ndt = 0.1\n'
                '[[perturb]]\nnode = 20\ndisplacement = [0.0, 0.01, 0.0]\n')
write("old", False)
write("new", True)
PY

# diff: the small element halves the exact step; it is named, the nodes matched by position.
expect_exit 1 "$DB" diff "$WORK/old.toml" "$WORK/new.toml" --frame-dt 1 --junit "$WORK/j.xml"
expect_match "$OUT" 'exact dt limit +0\.61457 s +0\.31795[0-9] s +-48\.3%' "limit halved"
expect_match "$OUT" '36 matched by position \(renumbered\)' "matched by position"
expect_match "$OUT" 'node 0 at \(2\.5, 0, -0\.3\): new' "the small element's node named"
expect_match "$OUT" 'spring 13-0 \(2, 0, 0\)-\(2\.5, 0, -0\.3\): new' "its spring named"
expect_match "$OUT" 'substeps of 1 s +2 +4' "substeps"
expect_match "$OUT" 'FAIL: the exact dt limit fell by 48\.3%' "verdict"
expect_match "$(cat "$WORK/j.xml")" '<failure message="the exact dt limit fell by 48\.3%' "JUnit"
expect_exit 0 "$DB" diff "$WORK/old.toml" "$WORK/new.toml" --max-drop 50
expect_exit 0 "$DB" diff "$WORK/old.toml" "$WORK/old.toml"
expect_match "$OUT" '^ok: the exact dt limit moved \+0%' "same scene"
# A baseline written by --save reads back with the same numbers.
expect_exit 0 "$DB" diff "$WORK/old.toml" --save "$WORK/base.json"
expect_exit 1 "$DB" diff "$WORK/base.json" "$WORK/new.toml"
expect_match "$OUT" 'exact dt limit +0\.61457 s' "baseline's limit"
expect_exit 0 "$DB" diff "$WORK/base.json" "$WORK/old.toml"
# bounds --json writes the same baseline (stdout only, byte for byte what diff --save wrote).
expect_exit 0 "$DB" bounds "$WORK/old.toml" --json
printf '%s\n' "$OUT" >"$WORK/bounds.json"
cmp -s "$WORK/bounds.json" "$WORK/base.json" && ok || bad "bounds --json differs from diff --save"
expect_exit 1 "$DB" diff "$WORK/bounds.json" "$WORK/new.toml"
expect_match "$OUT" 'exact dt limit +0\.61457 s' "bounds --json baseline's limit"
expect_exit 2 "$DB" bounds "$WORK/old.toml" --json --after 3
expect_one_line "$ERR" "bounds --json --after"
printf '{"format": "dampbound-limits", "version": 1' >"$WORK/cut.json"
expect_exit 2 "$DB" diff "$WORK/cut.json" "$WORK/old.toml"
expect_one_line "$ERR" "truncated baseline"
expect_match "$ERR" 'cut\.json: line 1: JSON' "names the file"
expect_exit 2 "$DB" diff "$WORK/old.toml"
expect_one_line "$ERR" "no NEW"

# [[expect]] limits: check guards them without a run.
cp "$WORK/old.toml" "$WORK/guard.toml"
printf '[[expect]]\ndt_limit_min = 0.6\nsubsteps_max = 2\nframe_dt = 1.0\n' >>"$WORK/guard.toml"
expect_exit 0 "$DB" check "$WORK/guard.toml"
printf '[[expect]]\ndt_limit_min = 0.62\n' >>"$WORK/guard.toml"
expect_exit 1 "$DB" check "$WORK/guard.toml"
expect_match "$OUT" 'dt_limit >= 0\.62 s' "the failing limit"

# --kappa-max on the two-node system: lambda = s kappa/m, c = gamma/m = 2, stable while
# s dt^2 < 4 - 2 c dt: s < 3.8 / 0.0025 = 1520; the contact ceiling 4 m/dt^2 - 2 gamma/dt - m R
# with R = 1: 1.6 - 0.08 - 0.001 = 1.519.
expect_exit 0 "$DB" suggest two-node --kappa-max --no-verify
expect_match "$OUT" 'all springs and anchors +1 springs +0 anchors +factor < 1520 ' "closed form"
expect_match "$OUT" 'min 1\.519, median 1\.519' "contact closed form"
expect_exit 0 "$DB" suggest stiff-region --kappa-max --no-verify --vtu "$WORK/c.vtu"
expect_match "$OUT" 'region 1 \(line 20\) +456 springs +169 anchors +factor < 72\.66' "per region"
expect_exit 0 /usr/bin/python3 -c "
import meshio, numpy as np
k = np.ravel(meshio.read('$WORK/c.vtu').point_data['contact_stiffness_max'])
assert k.shape == (1296,) and np.isfinite(k).all() and (k > 0).all(), k
"
# Over the factorisation budget, each knob says so in one line naming its flag, exit 3 as
# --equilibrium over the budget (before the budget reached them they factorised unbounded),
# and the damping kinds' rows say it per kind.
for knob in --kappa-max "--rayleigh 0.05" "--mass-scale 0.9"; do
  expect_exit 3 "$DB" suggest paper-plane $knob --no-verify --factor-budget 1e-9
  expect_one_line "$ERR" "$knob over the budget"
  expect_match "$ERR" "^dampbound: error: ${knob%% *}: not computed: one factorisation would take .* over the budget of 1e-09 GFlop \\(raise --factor-budget\\)" "$knob names the budget"
done
expect_exit 0 "$DB" suggest paper-plane --frame-dt 2 --no-verify --factor-budget 1e-9
expect_match "$OUT" '^answer +5 substeps per frame by the safe bound \(dt = 0\.4 s; not run: --no-verify\); the exact limit is over the factorisation budget$' "substeps: the safe count when the exact limit is over the budget"
expect_match "$OUT" 'exact limit not computed: one factorisation would take .* over the budget of 1e-09 GFlop' "substeps: the budget reaches the exact limit"
expect_exit 0 "$DB" suggest quad-cloth-dashpots --no-verify --factor-budget 1e-9
expect_match "$OUT" '^  kd +now [0-9.e-]+ +not computed: one factorisation would take .*\(--factor-budget\)' "a kind's range over the budget"
# --rayleigh: the pair, the closed form beside the exact index, the figure.
expect_exit 0 "$DB" suggest paper-plane --rayleigh 0.05 --plot "$WORK/z.png"
expect_match "$OUT" 'rayleigh_stiffness \(beta\) = 0\.0263501 s' "the pair"
expect_match "$OUT" 'stable for beta < 4\.82968 s \(exact index\); SPEC 10.s closed form 4\.82968 s' "closed form"
[ -s "$WORK/z.png" ] && ok || bad "no figure"
expect_exit 1 "$DB" suggest paper-plane --rayleigh 20
expect_match "$OUT" 'NOT stable: beta = 10\.5[0-9]* s is above .* the largest stable beta is 1\.0[0-9]* s, which reaches zeta' "beta above the step"
expect_exit 1 "$DB" suggest paper-plane --rayleigh 0.05,40
expect_match "$OUT" 'no Rayleigh pair gives these ratios: alpha would be negative' "no pair"
expect_exit 2 "$DB" suggest two-node --rayleigh 0.05
expect_match "$ERR" 'one frequency \(0\.159155 Hz\); give two with --band' "one mode"
expect_exit 0 "$DB" suggest two-node --rayleigh 0.05 --band 0.1:0.2
for bad_args in "--rayleigh abc" "--rayleigh 0.05 --band 2:1" "--band 1:2" "--vtu x.vtu" \
                "--kappa-max --rayleigh 0.1"; do
  # shellcheck disable=SC2086
  expect_exit 2 "$DB" suggest two-node $bad_args
  expect_one_line "$ERR" "suggest $bad_args"
done
finish
