#!/usr/bin/python3
"""A 10 000-trial sweep with dampbound and with vectorised NumPy, side by side.

dampbound runs the whole sweep (paper-plane scene, m and kappa = 0.001 .. 0.1 step 0.001,
zeta 0.5, policy fixed, dt 0.05, 1000 iterations: a 100 x 100 sample of --preset
paper-lower's grid, --no-similarity so every trial is stepped). NumPy runs the same step
(SPEC 1-5: spring and anchor forces, eq. 2 with the fixed gamma, semi-implicit Euler, the
first-entry protocol) on a random sample of those trials, all of them at once: every array
has one column per trial, forces are gathered and scattered with one sparse incidence matrix
product per step, and finished trials leave the batch. Its time per trial-step, times the
sweep's trial-steps (the iterations column of dampbound's CSV), is NumPy's time for the
sweep; the sample's outcomes and iterations are checked against dampbound's.

Prints both times, the ratio (wall and CPU), and the projected time of
`sweep --preset paper-lower` (3.42e8 trial-steps, docs/sweeps.md) at the measured rate.

Usage: bench/sweep_vs_numpy.py [--dampbound BUILD/app/dampbound] [--threads N]
                               [--sample K] [--step 0.001]
DAMPBOUND_KERNEL_ISA (generic, avx2, avx512) picks the kernel copy, as for every sweep.
"""
import argparse
import csv
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy.sparse as sp

PAPER_LOWER_TRIAL_STEPS = 3.42e8  # docs/sweeps.md: --preset paper-lower, similarity on


def paper_plane(n=36, spacing=0.57):
    """core/run/scene.cpp make_grid + paper_plane_scene: rest positions, springs, perturbed node."""
    rest = np.array([[a * spacing, 0.0, b * spacing] for a in range(n) for b in range(n)])
    springs = []
    for a in range(n):
        for b in range(n):
            i = a * n + b
            if a + 1 < n:
                springs.append((i, (a + 1) * n + b))
            if b + 1 < n:
                springs.append((i, a * n + b + 1))
            if a + 1 < n and b + 1 < n:
                springs.append((i, (a + 1) * n + b + 1))
    springs = np.array(springs)
    return rest, springs, (n // 2) * n + n // 2


def numpy_sweep(trials, dt=0.05, max_iter=1000, reference=5.0, restore=0.01, diverge=100.0):
    """Steps every trial of `trials` ((m, kappa, gamma) rows) at once until each restores,
    diverges or reaches max_iter. Returns (outcome, iterations) per trial and the trial-steps
    taken."""
    rest, springs, perturbed = paper_plane()
    n, s = len(rest), len(springs)
    i, j = springs[:, 0], springs[:, 1]
    l0 = np.linalg.norm(rest[j] - rest[i], axis=1)[:, None]  # rest lengths (S, 1)
    # D (S x n): +1 at j, -1 at i, so D x gives x_j - x_i, and -D^T f adds f = scale (x_j - x_i)
    # to node i's force and takes it from node j's (forces.cpp).
    d_mat = sp.csr_matrix((np.r_[np.ones(s), -np.ones(s)], (np.r_[np.arange(s), np.arange(s)],
                                                             np.r_[j, i])), shape=(s, n))
    d_t = d_mat.T.tocsr()
    t = len(trials)
    m, kappa, gamma = (np.array(c, dtype=float) for c in zip(*trials))
    x0 = np.repeat(rest[:, :, None], t, axis=2)  # (n, 3, T)
    x0[perturbed, 1, :] += 5.0
    x = x0.reshape(n, 3 * t)  # column c*T + k: component c of trial k
    v = np.zeros_like(x)
    rest_cols = np.repeat(rest, t, axis=1)
    live = np.arange(t)
    outcome = [None] * t
    iterations = [0] * t
    trial_steps = 0
    for it in range(1, max_iter + 1):
        k = len(live)
        mk = np.tile(m, 3)
        kk = np.tile(kappa, 3)
        gk = np.tile(gamma, 3)
        d = d_mat @ x  # (S, 3k)
        length = np.sqrt(d[:, :k] ** 2 + d[:, k:2 * k] ** 2 + d[:, 2 * k:] ** 2)
        scale = kappa * (length - l0) / length
        f = d * np.tile(scale, 3)
        force = -kk * (x - rest_cols) - d_t @ f
        a = (force - gk * v) / mk
        v = v + a * dt
        x = x + v * dt
        e = x - rest_cols
        disp = np.sqrt((e[:, :k] ** 2 + e[:, k:2 * k] ** 2 + e[:, 2 * k:] ** 2).max(axis=0))
        trial_steps += k
        done = np.zeros(k, dtype=bool)
        for c in range(k):
            r = disp[c]
            verdict = None
            if not np.isfinite(r) or not r <= diverge * reference:
                verdict = "diverged"
            elif r < restore * reference:
                verdict = "restored"
            elif it >= max_iter:
                verdict = "not_restored"
            if verdict:
                outcome[live[c]], iterations[live[c]], done[c] = verdict, it, True
        if done.any():
            keep = ~done
            cols = np.concatenate([keep] * 3)
            x, v, rest_cols = x[:, cols], v[:, cols], rest_cols[:, cols]
            m, kappa, gamma, live = m[keep], kappa[keep], gamma[keep], live[keep]
            if len(live) == 0:
                break
    return outcome, iterations, trial_steps


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--dampbound", default=os.path.join(here, "..", "build", "app", "dampbound"))
    ap.add_argument("--threads", type=int, default=os.cpu_count())
    ap.add_argument("--sample", type=int, default=48, help="trials NumPy runs (default 48)")
    ap.add_argument("--step", default="0.001", help="m and kappa step; 0.001 gives 10 000 trials")
    args = ap.parse_args()
    if args.sample < 1:
        sys.exit("sweep_vs_numpy.py: --sample must be >= 1")
    if not os.access(args.dampbound, os.X_OK):
        sys.exit(f"sweep_vs_numpy.py: --dampbound {args.dampbound}: not an executable; build it")
    version = subprocess.run([args.dampbound, "--version"], capture_output=True, text=True,
                             check=True).stdout.strip()
    axis = f"{args.step}:0.1:{args.step}"
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "sweep.csv")
        cmd = [args.dampbound, "sweep", "--m", axis, "--kappa", axis, "--zeta", "0.5",
               "--policy", "fixed", "--dt", "0.05", "--max-iter", "1000", "--no-similarity",
               "--threads", str(args.threads), "--progress", "none", "-o", out]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        db_wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        db_cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        with open(out) as fh:
            rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    sweep_steps = sum(int(r["iterations"]) for r in rows)
    rng = np.random.default_rng(2026)
    picked = rng.choice(len(rows), size=min(args.sample, len(rows)), replace=False)
    sample = [rows[k] for k in picked]
    trials = [(float(r["m"]), float(r["kappa"]), float(r["gamma"])) for r in sample]
    start, cpu0 = time.perf_counter(), time.process_time()
    outcome, iterations, np_steps = numpy_sweep(trials)
    np_wall, np_cpu = time.perf_counter() - start, time.process_time() - cpu0
    agree = sum(o == r["outcome"] and it == int(r["iterations"])
                for o, it, r in zip(outcome, iterations, sample))
    np_sweep_wall = np_wall / np_steps * sweep_steps
    np_sweep_cpu = np_cpu / np_steps * sweep_steps
    rate = sweep_steps / db_wall
    print(f"dampbound  {version}, {args.threads} threads: {len(rows)} trials, "
          f"{sweep_steps:.3g} trial-steps in {db_wall:.3g} s ({db_cpu:.3g} s CPU), "
          f"{rate:.3g} trial-steps/s")
    print(f"numpy      {np.__version__} (SciPy sparse products), "
          f"{len(trials)} sampled trials at once: {np_steps} trial-steps in {np_wall:.3g} s "
          f"({np_cpu:.3g} s CPU); same outcome and iterations as dampbound in {agree} of "
          f"{len(trials)}")
    print(f"numpy      projected for the sweep: {np_sweep_wall:.3g} s ({np_sweep_cpu:.3g} s CPU)")
    print(f"ratio      dampbound is {np_sweep_wall / db_wall:.3g}x NumPy by wall time, "
          f"{np_sweep_cpu / db_cpu:.3g}x by CPU time")
    print(f"paper-lower projected at {rate:.3g} trial-steps/s ({args.threads} threads): "
          f"{PAPER_LOWER_TRIAL_STEPS / rate / 60:.3g} min")


if __name__ == "__main__":
    main()
