#!/usr/bin/env bash
# The Python way: `pip install --no-build-isolation .` in a fresh venv that sees Debian's
# packages (numpy, scipy, setuptools; nothing downloaded), then import dampbound and check one
# number against SPEC 7's closed form. Prints how long the install took.
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=$(mktemp -d)
trap 'rm -rf "$venv"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$venv"
# After scripts/test.sh, CI's build/ already holds the module's objects: build the target
# there (seconds). Elsewhere setup.py configures build-pip/ (docs/guide.md, "Install and use it from your code").
if [ -f build/CMakeCache.txt ] && [ -z "${DAMPBOUND_CMAKE_BUILD_DIR+x}" ]; then
  export DAMPBOUND_CMAKE_BUILD_DIR=$PWD/build
fi
start=$SECONDS
"$venv/bin/pip" install --no-build-isolation --no-index --no-deps -q .
echo "pip-install: pip install took $((SECONDS - start)) s"
cd "$venv"  # away from the source tree: the installed module, not a build folder's
"$venv/bin/python" - <<'PY'
import math, dampbound, numpy as np, scipy.sparse as sp
print("dampbound", dampbound.__version__, "from", dampbound.__file__)
# Two nodes, one spring along x (kappa 1), unit masses: lambda_max of M^-1 K is 2.
K = sp.kron(sp.csr_matrix([[1.0, -1.0], [-1.0, 1.0]]), sp.csr_matrix(np.diag([1.0, 0, 0])))
r = dampbound.linear_limits(K + 1e-3 * sp.identity(6), [1.0, 1.0], dt=0.1, gamma=0.1)
assert math.isclose(r.lambda_max[1], 2.001, rel_tol=1e-9), r.lambda_max
assert math.isclose(r.dt_max, (math.sqrt(0.01 + 4 * 2.001) - 0.1) / 2.001, rel_tol=1e-9)
print("pip-install: linear_limits ok:", r)
PY
