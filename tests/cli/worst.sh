# bounds --worst N: the nodes that limit dt and gamma, and why.
. "$(dirname "$0")/lib.inc"

expect_exit 0 "$DB" bounds "$SRC/scenes/paper-plane.toml" --worst 2
expect_match "$OUT" 'worst 2 by dt_safe_i' "text table"
expect_match "$OUT" 'typical node' "uniform plane: typical"
expect_exit 0 "$DB" bounds "$SRC/scenes/tissue-cap.toml" --worst 1 --json
expect_match "$OUT" '^\{"median_mass":.*"by_dt_safe":\[\{"node":0,.*"cause":"degree [0-9.]+x above the median"' "JSON, cause in words"
# --json without --worst: the limits baseline diff reads (tests/cli/knobs.sh); none without a scene.
expect_exit 0 "$DB" bounds paper-plane --json
expect_match "$OUT" '^\{"format": *"dampbound-limits"' "bounds --json: the baseline"
expect_exit 2 "$DB" bounds --m 1 --kappa 1 --dt 0.1 --json
expect_one_line "$ERR" "bounds --json without a scene"

# The VTU files carry dt_safe, gamma_safe and zeta per point (read back with meshio).
expect_exit 0 "$DB" run "$SRC/scenes/tissue-cap.toml" --max-iter 2 --vtk "$WORK/vtk"
expect_exit 0 /usr/bin/python3 -c "
import glob, meshio, math
f = sorted(glob.glob('$WORK/vtk/*.vtu'))[0]
pd = meshio.read(f).point_data
assert {'dt_safe', 'gamma_safe', 'zeta'} <= set(pd), sorted(pd)
import numpy as np
dt, gs, z = (np.ravel(pd[k]) for k in ('dt_safe', 'gamma_safe', 'zeta'))
assert (dt >= 0).all() and dt.max() > 0 and np.isfinite(gs).all()
lo, g = np.ravel(pd['lower']), np.ravel(pd['effective_damping'])  # iteration 0: the user's gamma_i
m = (lo > 0) & (dt > 0)  # free nodes with a ratio
assert m.any() and np.allclose(z[m], g[m] / lo[m], rtol=1e-12, atol=0)
"
finish
