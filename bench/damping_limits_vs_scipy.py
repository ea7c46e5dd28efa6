#!/usr/bin/python3
"""SPEC 10's exact gamma and dt limits of a scene: dampbound's (damping_limits_bench:
definiteness of 4 I - S by sparse Cholesky on one pattern analysis) against an independent
SciPy route on the same matrices, in one run.

    /usr/bin/python3 bench/damping_limits_vs_scipy.py [--bench build/bench/damping_limits_bench]
        [SCENE ...]   (default: scenes/tissue-block-rayleigh.toml scenes/quad-cloth-dashpots.toml)

The SciPy route shares nothing with dampbound's: with A, C = Cp + gamma G (weighted, as the
benchmark writes them) and S(dt) = dt^2 A + 2 dt C, the step is stable iff 4 I - S is positive
definite (SPEC 10). gamma limit: the smallest eigenvalue mu of (4 I - dt^2 A - 2 dt Cp) v =
mu (2 dt G) v, by eigsh in shift-invert mode at 0 (SuperLU), gamma_max = mu. dt limit: bisection
on h to 1e-10 relative, each step an LDL^T by SuperLU with symmetric ordering and diagonal
pivots (SymmetricMode, diag_pivot_thresh 0), positive definite iff every pivot is positive.
Processor times (this process's, and the benchmark's own); ratio = SciPy / dampbound.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy.sparse
import scipy.sparse.linalg


def load(path):
    with open(path, "rb") as f:
        n, nnz = np.fromfile(f, dtype="<i8", count=2)
        outer = np.fromfile(f, dtype="<i8", count=n + 1)
        inner = np.fromfile(f, dtype="<i4", count=nnz)
        values = np.fromfile(f, dtype="<f8", count=nnz)
    return scipy.sparse.csc_matrix((values, inner, outer), shape=(n, n))


def positive_definite(B):
    """Every pivot of a symmetric-mode LU without row exchanges is positive (Sylvester)."""
    try:
        lu = scipy.sparse.linalg.splu(B.tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                                      options=dict(SymmetricMode=True))
    except RuntimeError:  # an exactly singular pivot
        return False
    if np.any(lu.perm_r != lu.perm_c):
        raise SystemExit("SuperLU exchanged rows: pivots no longer give the inertia")
    return bool(np.all(lu.U.diagonal() > 0))


def scipy_limits(A, Cp, G, gamma, dt):
    n = A.shape[0]
    I = scipy.sparse.identity(n, format="csc")
    B0 = (4 * I - dt * dt * A - 2 * dt * Cp).tocsc()
    U = (2 * dt * G).tocsc()
    mu = scipy.sparse.linalg.eigsh(B0, k=1, M=U, sigma=0, which="LM", return_eigenvectors=False)[0]
    C = (Cp + gamma * G).tocsc()
    S = lambda h: (h * h * A + 2 * h * C).tocsc()
    lo, hi = dt, dt
    while positive_definite(4 * I - S(hi)):
        lo, hi = hi, 2 * hi
    while not positive_definite(4 * I - S(lo)):
        hi, lo = lo, lo / 2
    while hi - lo > 1e-10 * hi:
        mid = 0.5 * (lo + hi)
        if positive_definite(4 * I - S(mid)):
            lo = mid
        else:
            hi = mid
    return mu, lo


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", default=os.path.join(here, "..", "build", "bench", "damping_limits_bench"))
    ap.add_argument("scenes", nargs="*", default=[os.path.join(here, "..", "scenes", s) for s in
                                                  ("tissue-block-rayleigh.toml", "quad-cloth-dashpots.toml")])
    a = ap.parse_args()
    if not os.path.exists(a.bench):
        sys.exit(f"damping_limits_vs_scipy.py: {a.bench} not built (cmake --build build --target damping_limits_bench)")
    print(f"{'scene':28}{'rows':>7}  {'dampbound gamma_max, dt_max':>30}{'cpu s':>8}  "
          f"{'SciPy gamma_max, dt_max':>30}{'cpu s':>8}{'ratio':>7}")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes:
            prefix = os.path.join(tmp, "m")
            out = subprocess.run([a.bench, scene, "--matrix", prefix, "--repeats", "3"],
                                 check=True, capture_output=True, text=True).stdout
            r = dict(kv.split("=", 1) for kv in out.split())
            A, Cp, G = (load(prefix + s) for s in (".A", ".Cp", ".G"))
            c = time.process_time()
            mu, h = scipy_limits(A, Cp, G, float(r["gamma"]), float(r["dt"]))
            cpu = time.process_time() - c
            ours = float(r["limits_cpu_best_s"])
            name = os.path.basename(scene)
            print(f"{name:28}{r['rows']:>7}  {float(r['gamma_max']):>14.9g}, {float(r['dt_max']):<14.9g}"
                  f"{ours:>8.3f}  {mu:>14.9g}, {h:<14.9g}{cpu:>8.2f}{cpu / max(ours, 1e-3):>6.0f}x")


if __name__ == "__main__":
    main()
