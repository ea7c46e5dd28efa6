"""An independent NumPy step of SPEC 10 (nodal, dashpot and Rayleigh damping) on a small mesh,
compared with `dampbound run --trace`: the watched node's displacement, eq. 6 generalised
(gamma_hi with D' counted), the generalised safe bound gamma_safe and the largest displacement,
iteration by iteration. The reference assembles K(x) and C' as dense matrices (the step applies
them spring by spring). Usage: damping_reference.py DAMPBOUND WORKDIR [policy] [integrator]."""
import csv
import subprocess
import sys

import numpy as np

db, work = sys.argv[1], sys.argv[2]
policy = sys.argv[3] if len(sys.argv) > 3 else "fixed"
rng = np.random.default_rng(7)
n_side, h = 4, 0.57
m, kappa, gamma, dt = 0.002, 0.003, 0.001, 0.05
kd, alpha, beta = 0.004, 0.3, 0.02
X = np.array([[a * h, 0.0, b * h] for a in range(n_side) for b in range(n_side)])
n = len(X)
mass_scale = rng.uniform(0.5, 2.0, n)
anchor_scale = np.where(rng.uniform(size=n) < 0.7, rng.uniform(0.5, 1.5, n), 0.0)
fixed = np.zeros(n, bool)
fixed[0] = True
springs = []
for a in range(n_side):
    for b in range(n_side):
        i = a * n_side + b
        if a + 1 < n_side:
            springs.append((i, i + n_side))
        if b + 1 < n_side:
            springs.append((i, i + 1))
        if a + 1 < n_side and b + 1 < n_side:
            springs.append((i, i + n_side + 1))
kscale = rng.uniform(0.5, 2.0, len(springs))
dscale = rng.uniform(0.0, 2.0, len(springs))
rest = np.array([np.linalg.norm(X[j] - X[i]) for i, j in springs])
# Some springs at another rest length: tension and compression at rest.
rest[::5] *= 1.2
rest[1::7] *= 0.8
watch = 6
x0 = X.copy()
x0[watch] += [0.1, 0.4, -0.05]
v0 = np.zeros((n, 3))
v0[watch + 4] = [0.0, 0.3, 0.1]

lines = ['name = "damping-reference"', f"watch = {watch}"]
for i in range(n):
    lines += ["[[node]]", "x = [%r, %r, %r]" % tuple(X[i]), f"mass_scale = {mass_scale[i]!r}",
              f"anchor_scale = {anchor_scale[i]!r}", f"fixed = {'true' if fixed[i] else 'false'}"]
for k, (i, j) in enumerate(springs):
    lines += ["[[spring]]", f"nodes = [{i}, {j}]", f"kappa_scale = {kscale[k]!r}",
              f"kd_scale = {dscale[k]!r}", f"rest_length = {rest[k]!r}"]
lines += ["[params]", f"m = {m!r}", f"kappa = {kappa!r}", f"gamma = {gamma!r}", f"dt = {dt!r}",
          f'policy = "{policy}"', f"kd = {kd!r}", f"rayleigh_mass = {alpha!r}",
          f"rayleigh_stiffness = {beta!r}"]
lines += ["[[perturb]]", f"node = {watch}", "displacement = [%r, %r, %r]" % tuple(x0[watch] - X[watch])]
lines += ["[[perturb]]", f"node = {watch + 4}", "displacement = [0.0, 0.0, 0.0]",
          "velocity = [%r, %r, %r]" % tuple(v0[watch + 4])]
lines += ["[protocol]", "max_iterations = 120"]
scene = f"{work}/damping-reference.toml"
with open(scene, "w") as f:
    f.write("\n".join(lines) + "\n")
trace = f"{work}/damping-reference.csv"
subprocess.run([db, "run", scene, "--rule", "settled", "--trace", trace], check=True,
               stdout=subprocess.DEVNULL)
rows = list(csv.DictReader(open(trace)))

M = m * mass_scale
KA = kappa * anchor_scale
KS = kappa * kscale
KD = kd * dscale
KDA = np.where(anchor_scale > 0, kd, 0.0)
free = ~fixed


def blocks(x):
    """Dense K(x) and the dashpot matrix (3n x 3n, every node), and the internal forces."""
    K = np.zeros((3 * n, 3 * n))
    P = np.zeros((3 * n, 3 * n))
    F = -KA[:, None] * (x - X)
    for k, (i, j) in enumerate(springs):
        dl = x[j] - x[i]
        l = np.linalg.norm(dl)
        d = dl / l
        F[i] += KS[k] * (l - rest[k]) * d
        F[j] -= KS[k] * (l - rest[k]) * d
        B = KS[k] * (rest[k] / l * np.outer(d, d) + (1 - rest[k] / l) * np.eye(3))
        D = KD[k] * np.outer(d, d)
        for (p, q, s) in ((i, i, 1), (j, j, 1), (i, j, -1), (j, i, -1)):
            K[3 * p:3 * p + 3, 3 * q:3 * q + 3] += s * B
            P[3 * p:3 * p + 3, 3 * q:3 * q + 3] += s * D
    for i in range(n):
        K[3 * i:3 * i + 3, 3 * i:3 * i + 3] += KA[i] * np.eye(3)
        P[3 * i:3 * i + 3, 3 * i:3 * i + 3] += KDA[i] * np.eye(3)
    return K, P, F


dofs = np.repeat(free, 3)
x, v = x0.copy(), v0.copy()
worst = 0.0
for row in rows:
    K, P, F = blocks(x)
    Cp = alpha * np.diag(np.repeat(M, 3)) + beta * K + P
    vf = np.where(free[:, None], v, 0.0).reshape(-1)
    Dp = (Cp @ vf).reshape(n, 3)
    G = np.full(n, gamma)
    # eq. 6 generalised and the generalised safe bound at the watched node (the step's state at t)
    hi = np.linalg.norm(v[watch] * M[watch] / dt + F[watch] - Dp[watch]) / np.linalg.norm(v[watch]) \
        if np.linalg.norm(v[watch]) > 0 else np.inf
    w = 1 / np.sqrt(np.repeat(M, 3))
    A = (w[:, None] * K * w[None, :])[np.ix_(dofs, dofs)]
    Ch = (w[:, None] * Cp * w[None, :])[np.ix_(dofs, dofs)]
    W = 2 * dt * Ch + dt * dt * A
    idx = {node: b for b, node in enumerate(np.flatnonzero(free))}
    margins = []
    for r in range(3):
        rr = 3 * idx[watch] + r
        margins.append(4 - W[rr, rr] - (np.abs(W[rr]).sum() - abs(W[rr, rr])))
    safe = M[watch] / (2 * dt) * min(margins)
    lo = 2 * np.sqrt(M[watch] * max([KA[watch]] + [KS[k] for k, s in enumerate(springs) if watch in s]))
    geff = gamma if policy == "fixed" else min(max(gamma, lo), safe) if lo <= safe else max(safe, 0)
    if policy == "safe":
        # every node's own clamp
        G = np.zeros(n)
        for node in np.flatnonzero(free):
            mg = []
            for r in range(3):
                rr = 3 * idx[node] + r
                mg.append(4 - W[rr, rr] - (np.abs(W[rr]).sum() - abs(W[rr, rr])))
            sf = M[node] / (2 * dt) * min(mg)
            ln = 2 * np.sqrt(M[node] * max([KA[node]] + [KS[k] for k, s in enumerate(springs) if node in s]))
            G[node] = min(max(gamma, ln), sf) if ln <= sf else max(sf, 0)
    a = (F - Dp - G[:, None] * v) / M[:, None]
    v = np.where(free[:, None], v + a * dt, v)
    x = np.where(free[:, None], x + v * dt, x)
    disp = np.linalg.norm(x[watch] - X[watch])
    maxd = np.linalg.norm(x - X, axis=1).max()
    for name, want in (("displacement", disp), ("upper_bound", hi), ("safe_bound", safe),
                       ("max_displacement", maxd), ("gamma_effective", G[watch] if policy == "safe" else gamma)):
        got = float(row[name])
        err = abs(got - want) / max(abs(want), 1e-12) if np.isfinite(want) else (0 if got == want else 1)
        worst = max(worst, err)
        if err > 1e-8:
            print(f"iteration {row['iteration']}: {name} {got!r} against the reference {want!r}")
            sys.exit(1)
print(f"{len(rows)} iterations, largest relative difference {worst:.2e}")
