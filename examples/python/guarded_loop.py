"""A plain NumPy mass-spring loop (the paper's step, SPEC 2) guarded by dampbound's monitor.

A 12 x 12 grid anchored to its rest positions, one node pulled 5 cm out of the plane, stepped
with semi-implicit Euler at the paper's Fig. 1 values (m = kappa = 0.001, dt = 0.05 s) and no
damping (gamma = 0, below the lower bound 2 sqrt(m kappa) = 0.002 of eq. 5): on its own the
loop does not settle in 1000 steps; the same loop asking the monitor each step for the
effective damping of the safe policy (gamma clamped into [gamma_lo_i, gamma_safe_i], SPEC 9,
from the positions and velocities at t) settles. Exits 1 when that is not what happens.
"""
import sys

import numpy as np

import dampbound

n, h, m, kappa, dt, gamma = 12, 0.57, 0.001, 0.001, 0.05, 0.0
a, b = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
rest = np.stack([a.ravel() * h, np.zeros(n * n), b.ravel() * h], axis=1)
idx = (a * n + b)
springs = np.concatenate([
    np.stack([idx[:-1, :].ravel(), idx[1:, :].ravel()], 1),    # (a, b)-(a+1, b)
    np.stack([idx[:, :-1].ravel(), idx[:, 1:].ravel()], 1),    # (a, b)-(a, b+1)
    np.stack([idx[:-1, :-1].ravel(), idx[1:, 1:].ravel()], 1)])  # (a, b)-(a+1, b+1)
l0 = np.linalg.norm(rest[springs[:, 1]] - rest[springs[:, 0]], axis=1)
mass, k = np.full(n * n, m), np.full(len(springs), kappa)

monitor = dampbound.Monitor(mass, springs, k, l0,
                            anchor_stiffness=np.full(n * n, kappa), rest=rest)


def forces(x):
    """F_i: springs and anchors (SPEC 1), the user's own NumPy code."""
    d = x[springs[:, 1]] - x[springs[:, 0]]
    length = np.linalg.norm(d, axis=1)
    pull = (k * (length - l0) / length)[:, None] * d
    f = -kappa * (x - rest)
    np.add.at(f, springs[:, 0], pull)
    np.add.at(f, springs[:, 1], -pull)
    return f


def run(policy):
    x, v = rest.copy(), np.zeros_like(rest)
    x[(n // 2) * n + n // 2, 1] += 5.0
    g = np.full(n * n, gamma)
    for it in range(1, 1001):
        f = forces(x)
        if policy:  # the guard: one call per step, arrays read in place
            _, g = monitor.check(v, f, np.full(n * n, gamma), dt, policy=policy, x=x)
        v += (f - g[:, None] * v) / mass[:, None] * dt   # eq. 3
        x += v * dt                                      # eq. 4
        if np.max(np.linalg.norm(x - rest, axis=1)) < 0.05:
            return it
    return None


plain, guarded = run(None), run("safe")
print(f"gamma = {gamma} (eq. 5 lower bound {monitor.lower_bounds()[0]:.4f})")
print(f"plain loop:   {'restored at ' + str(plain) if plain else 'not restored in 1000 steps'}")
print(f"guarded loop: {'restored at ' + str(guarded) if guarded else 'not restored in 1000 steps'}")
sys.exit(0 if plain is None and guarded is not None else 1)
