"""The knobs from Python (kappa_ceiling, rayleigh_from_spectrum, diff_limits, save_limits),
each against an independent NumPy computation on a small anchored square: the dense
amplification matrix of the paper's step, the dense Gershgorin rows, the dense spectrum."""
import math

import numpy as np
import pytest

import dampbound

X = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 0.0, 1.0], [0.5, 0.0, 0.5]])
SPRINGS = [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 4), (2, 4), (3, 4)]
MASS = [1.0, 1.0, 0.5, 1.0, 2.0]
M, KAPPA, GAMMA, DT = 0.001, 0.001, 0.0005, 0.3


def scene_file(tmp_path, name="square", stiff=1.0):
    lines = [f'name = "{name}"']
    for i, x in enumerate(X):
        lines += ["[[node]]", "x = [%r, %r, %r]" % tuple(x), f"mass_scale = {MASS[i]}",
                  "anchor_scale = 0.5", f"fixed = {'true' if i == 0 else 'false'}"]
    for k, (i, j) in enumerate(SPRINGS):
        lines += ["[[spring]]", f"nodes = [{i}, {j}]"]
        if k == 6:
            lines += [f"kappa_scale = {stiff}"]
    lines += ["[params]", f"m = {M}", f"kappa = {KAPPA}", f"gamma = {GAMMA}", f"dt = {DT}",
              'policy = "fixed"', "[[perturb]]", "node = 2", "displacement = [0.0, 0.05, 0.0]",
              "[protocol]", "max_iterations = 3000"]
    path = tmp_path / f"{name}.toml"
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def dense(factor=1.0, stiff=1.0):
    """K, M^-1 and C over the free nodes (1..4) at rest, every stiffness times factor."""
    free = [1, 2, 3, 4]
    n = 3 * len(free)
    K = np.zeros((n, n))
    at = {node: 3 * b for b, node in enumerate(free)}
    for k, (i, j) in enumerate(SPRINGS):
        d = (X[j] - X[i]) / np.linalg.norm(X[j] - X[i])
        B = factor * KAPPA * (stiff if k == 6 else 1.0) * np.outer(d, d)
        for a, b, s in ((i, i, 1), (j, j, 1), (i, j, -1), (j, i, -1)):
            if a in at and b in at:
                K[at[a]:at[a] + 3, at[b]:at[b] + 3] += s * B
    for node in free:
        K[at[node]:at[node] + 3, at[node]:at[node] + 3] += factor * 0.5 * KAPPA * np.eye(3)
    minv = np.repeat([1 / (M * MASS[i]) for i in free], 3)
    C = GAMMA * np.eye(n)
    return K, minv, C


def radius(K, minv, C, dt):
    n = K.shape[0]
    I = np.eye(n)
    MK, MC = minv[:, None] * K, minv[:, None] * C
    T = np.block([[I - dt * dt * MK, dt * (I - dt * MC)], [-dt * MK, I - dt * MC]])
    return max(abs(np.linalg.eigvals(T)))


def test_kappa_ceiling_matches_the_dense_amplification_matrix(tmp_path):
    scene = dampbound.load_scene(scene_file(tmp_path))
    r = dampbound.kappa_ceiling(scene)
    whole = r["ceilings"][0]
    assert whole["label"] == "all springs and anchors" and whole["springs"] == 8
    lo, hi = 0.5 * whole["factor"], 1.5 * whole["factor"]
    assert radius(*dense(lo), DT) < 1 < radius(*dense(hi), DT)
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if radius(*dense(mid), DT) < 1 else (lo, mid)
    assert whole["factor"] == pytest.approx(lo, rel=1e-7)
    assert whole["below_settles"] is True and whole["above_settles"] is False
    assert whole["below"].outcome == "settled"


def test_contact_ceiling_is_the_closed_form_of_the_rows(tmp_path):
    scene = dampbound.load_scene(scene_file(tmp_path))
    k = dampbound.kappa_ceiling(scene, verify=False)["contact_stiffness_max"]
    assert k.shape == (5,) and math.isnan(k[0])
    K, minv, C = dense()
    A = np.sqrt(minv)[:, None] * K * np.sqrt(minv)[None, :]
    Ch = np.sqrt(minv)[:, None] * C * np.sqrt(minv)[None, :]
    for b, node in enumerate([1, 2, 3, 4]):
        def margin(extra):
            Q = 4 * np.eye(len(A)) - 2 * DT * Ch - DT * DT * A
            rows = range(3 * b, 3 * b + 3)
            for r in rows:
                Q[r, r] -= DT * DT * extra * minv[r]
            return min(2 * Q[r, r] - np.abs(Q[r]).sum() for r in rows)
        assert k[node] > 0
        assert margin(k[node] * (1 - 1e-7)) > 0 > margin(k[node] * (1 + 1e-7))


def test_rayleigh_pair_reproduces_the_ratios_on_the_dense_spectrum(tmp_path):
    scene = dampbound.load_scene(scene_file(tmp_path))
    K, minv, C0 = dense()
    lam = np.linalg.eigvalsh(np.sqrt(minv)[:, None] * K * np.sqrt(minv)[None, :])
    verdicts = []
    for z1, z2 in ((0.05, 0.08), (3.0, 3.0)):
        r = dampbound.rayleigh_from_spectrum(scene, z1, z2)
        assert r["lambda_min"] == pytest.approx(lam.min(), rel=1e-9)
        assert r["lambda_max"] == pytest.approx(lam.max(), rel=1e-9)
        assert r["feasible"]
        for f, z in ((r["f1"], z1), (r["f2"], z2)):
            w = 2 * math.pi * f
            assert r["alpha"] / (2 * w) + r["beta"] * w / 2 == pytest.approx(z, rel=1e-9)
        # The verdict against the dense step with the pair.
        C = C0 + r["alpha"] * np.diag(1 / minv) + r["beta"] * K
        assert r["stable"] == (radius(K, minv, C, DT) < 1)
        verdicts.append(r["stable"])
    assert verdicts == [True, False]
    # 0.02 at f1 and 0.1 at f2 need alpha < 0 on this narrow spectrum: no pair.
    assert not dampbound.rayleigh_from_spectrum(scene, 0.02, 0.1)["feasible"]
    band = dampbound.rayleigh_from_spectrum(scene, 0.05, band=(0.01, 0.1))
    assert (band["f1"], band["f2"]) == (0.01, 0.1)
    with pytest.raises(ValueError):
        dampbound.rayleigh_from_spectrum(scene, 0.05, band=(0.1, 0.01))


def test_diff_limits_names_the_stiff_spring_and_reads_a_baseline(tmp_path):
    old = dampbound.load_scene(scene_file(tmp_path, "old"))
    new = dampbound.load_scene(scene_file(tmp_path, "new", stiff=40.0))
    base = str(tmp_path / "base.json")
    saved = dampbound.save_limits(old, base)
    d = dampbound.diff_limits(base, new, frame_dt=1.0)
    assert d["old"]["dt_limit"] == saved["dt_limit"]
    assert d["drop"] > 0.2 and d["failed"]
    assert d["changes"][0][0].startswith("spring 2-4 ") and "kappa x40" in d["changes"][0][0]
    assert d["substeps"][1] >= d["substeps"][0]
    same = dampbound.diff_limits(old, base)
    assert same["drop"] == 0 and not same["failed"] and same["changes"] == []
