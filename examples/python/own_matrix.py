"""Your own matrices: a linear-elastic FEM stiffness assembled with NumPy/SciPy (constant-strain
tetrahedra on a Kuhn-split block, bottom face clamped by removing its nodes), lumped masses,
nodal damping; dampbound.linear_limits says which dt and damping keep the paper's step stable,
with the same certified analysis `dampbound bounds` runs on a scene (docs/embedding.md)."""
import itertools

import numpy as np
import scipy.sparse as sp

import dampbound

# A 6 x 3 x 3 block of 1 cm cubes, each split into 6 tetrahedra along its diagonal (Kuhn).
nx, ny, nz, h = 6, 3, 3, 1.0
idx = lambda a, b, c: (a * (ny + 1) + b) * (nz + 1) + c
points = np.array([[a * h, b * h, c * h] for a in range(nx + 1) for b in range(ny + 1)
                   for c in range(nz + 1)])
tets = []
for a, b, c in itertools.product(range(nx), range(ny), range(nz)):
    for perm in itertools.permutations(range(3)):
        corner, path = [a, b, c], [idx(a, b, c)]
        for axis in perm:
            corner[axis] += 1
            path.append(idx(*corner))
        tets.append(path)
tets = np.array(tets)

# Isotropic linear elasticity (E in mass unit / (cm s^2), nu), density in mass unit / cm^3.
E, nu, rho = 50.0, 0.3, 1e-3
lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
D = lam * np.outer([1, 1, 1, 0, 0, 0], [1, 1, 1, 0, 0, 0]) + mu * np.diag([2, 2, 2, 1, 1, 1])
rows, cols, vals = [], [], []
mass = np.zeros(len(points))
for t in tets:
    X = np.c_[np.ones(4), points[t]]
    V = abs(np.linalg.det(X)) / 6  # either orientation: |V|
    grad = np.linalg.inv(X)[1:]    # shape-function gradients, 3 x 4
    B = np.zeros((6, 12))
    for k in range(4):
        gx, gy, gz = grad[:, k]
        B[:, 3 * k:3 * k + 3] = [[gx, 0, 0], [0, gy, 0], [0, 0, gz],
                                 [gy, gx, 0], [0, gz, gy], [gz, 0, gx]]
    Ke = V * B.T @ D @ B
    dofs = np.ravel([[3 * i, 3 * i + 1, 3 * i + 2] for i in t])
    rows.append(np.repeat(dofs, 12))
    cols.append(np.tile(dofs, 12))
    vals.append(Ke.ravel())
    mass[t] += rho * V / 4
K = sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                  shape=(3 * len(points),) * 2).tocsr()

# Clamp the face x = 0: its nodes never move, so they have no rows (as fixed nodes in a scene).
free = np.flatnonzero(points[:, 0] > 0)
dofs = np.ravel([[3 * i, 3 * i + 1, 3 * i + 2] for i in free])
K_free = K[dofs][:, dofs]
K_free = (K_free + K_free.T) / 2  # symmetric to the last bit

dt, gamma = 2e-3, 1e-4
r = dampbound.linear_limits(K_free, mass[free], dt=dt, gamma=gamma)
lo, hi = r.lambda_max
print(f"{len(free)} free nodes, {len(tets)} tetrahedra")
print(f"lambda_max of M^-1 K in [{lo:.6g}, {hi:.6g}] 1/s^2 (certified)")
print(f"at gamma = {gamma:g}: stable for dt < dt_max = {r.dt_max:.4g} s; "
      f"at dt = {dt:g} s: stable for {r.gamma_min:.3g} <= gamma < {r.gamma_max:.4g}")
print(f"the given gamma and dt are {'stable' if r.stable else 'NOT stable'}")
worst = int(np.argmin(r.dt_safe))
print(f"SPEC 9 per node: smallest dt_safe {r.dt_safe[worst]:.4g} s at node {free[worst]}, "
      f"smallest gamma_safe {r.gamma_safe.min():.4g}")
assert r.stable == (dt < r.dt_max)
assert r.dt_safe.min() <= r.dt_max  # the local bound is sufficient, so never above the exact one
