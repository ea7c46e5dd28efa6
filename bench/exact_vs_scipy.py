#!/usr/bin/python3
"""lambda_max of M^-1/2 K M^-1/2 on big meshes: dampbound's certified sparse-Cholesky method
against SciPy's eigsh (ARPACK Lanczos, which='LA') on the same matrix, in one run.

    /usr/bin/python3 bench/exact_vs_scipy.py [--bench build/bench/exact_limits_bench]
                                    [--planes 100,200,400] [--blocks 20] [--no-scipy-above N]

For each mesh the C++ benchmark builds the matrix, times its own method, and writes the
matrix; this script loads it and times eigsh, then prints both times, both values and the
ratio. Needs python3-scipy (Debian). Times are wall-clock seconds on whatever else the machine
is doing: run it on otherwise idle cores. The C++ side runs its Lanczos products on every CPU
(the same bits as on one); its processor time, which the ratio uses, counts every thread.
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
    return scipy.sparse.csc_matrix((values, inner, outer), shape=(n, n)).tocsr()


def blas_in_use():
    """The BLAS library this process loaded (through numpy/scipy): the alternative Debian
    selected, or what LD_LIBRARY_PATH put first; the benchmark inherits the same lookup."""
    with open("/proc/self/maps") as f:
        paths = {line.split()[-1] for line in f if "libblas" in line or "openblas" in line}
    return ", ".join(sorted(os.path.realpath(p) for p in paths)) or "unknown"


def run(bench, kind, n, scipy_limit):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "A.bin")
        line = subprocess.run([bench, kind, str(n), "--matrix", path], check=True,
                              capture_output=True, text=True).stdout.strip()
        ours = dict(kv.split("=", 1) for kv in line.split())
        A = load(path)
    nodes = int(ours["nodes"])
    row = {"mesh": f"{kind} {n}" + ("x%d" % n if kind == "plane" else "^3"), "nodes": nodes,
           "springs": int(ours["springs"]), "ours_s": float(ours["lambda_s"]),
           "ours_cpu": float(ours["lambda_cpu_s"]), "all_s": float(ours["all_limits_s"]),
           "all_cpu": float(ours["all_limits_cpu_s"]), "lo": float(ours["lambda_max_lo"]),
           "hi": float(ours["lambda_max_hi"]), "fact": int(ours["factorizations"]),
           "solves": int(ours["solves"]), "steps": int(ours["lanczos_steps"])}
    if nodes > scipy_limit:
        row["scipy_s"] = None
        return row
    t, c = time.perf_counter(), time.process_time()
    value = scipy.sparse.linalg.eigsh(A, k=1, which="LA", return_eigenvectors=False)[0]
    row["scipy_s"] = time.perf_counter() - t
    row["scipy_cpu"] = time.process_time() - c
    row["scipy"] = float(value)
    return row


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bench", default=os.path.join(here, "..", "build", "bench", "exact_limits_bench"))
    ap.add_argument("--planes", default="100,200,400", help="plane sizes n (n x n nodes)")
    ap.add_argument("--blocks", default="", help="tetrahedral block sizes n (n^3 nodes)")
    ap.add_argument("--no-scipy-above", type=int, default=10**9,
                    help="skip eigsh on meshes with more nodes than this")
    a = ap.parse_args()
    if not os.access(a.bench, os.X_OK):
        sys.exit(f"exact_vs_scipy.py: {a.bench} not built (cmake --build build --target exact_limits_bench)")
    cases = [("plane", int(s)) for s in a.planes.split(",") if s] + \
            [("block", int(s)) for s in a.blocks.split(",") if s]
    print("times: wall clock s (processor s); ratio = eigsh / dampbound, of processor times")
    print(f"BLAS (this process and the benchmark's): {blas_in_use()}; {os.cpu_count()} cores")
    print(f"{'mesh':<14}{'nodes':>9}{'springs':>9}  {'dampbound lambda_max':>21}{'all limits':>18}"
          f"{'steps/fact/solves':>18}  {'eigsh':>18}{'ratio':>8}  lambda_max certified [lo, hi] / eigsh")
    for kind, n in cases:
        r = run(a.bench, kind, n, a.no_scipy_above)
        sci = ("%8.2f (%7.2f)" % (r["scipy_s"], r["scipy_cpu"])) if r["scipy_s"] is not None else "%18s" % "-"
        ratio = "%7.0fx" % (r["scipy_cpu"] / max(r["ours_cpu"], 1e-9)) if r["scipy_s"] is not None else "%8s" % "-"
        value = ("%.10g" % r["scipy"]) if r["scipy_s"] is not None else "-"
        inside = "" if r["scipy_s"] is None else (
            "  (eigsh inside)" if r["lo"] - 1e-9 * abs(r["hi"]) <= r["scipy"] <= r["hi"] + 1e-9 * abs(r["hi"])
            else "  (eigsh OUTSIDE)")
        ours = "%9.3f (%8.3f)" % (r["ours_s"], r["ours_cpu"])
        alls = "%7.3f (%7.3f)" % (r["all_s"], r["all_cpu"])
        print(f"{r['mesh']:<14}{r['nodes']:>9}{r['springs']:>9}  {ours:>21}{alls:>18}"
              f"{'%d/%d/%d' % (r['steps'], r['fact'], r['solves']):>18}  {sci}{ratio}  "
              f"[{r['lo']:.10g}, {r['hi']:.10g}] / {value}{inside}", flush=True)


if __name__ == "__main__":
    main()
