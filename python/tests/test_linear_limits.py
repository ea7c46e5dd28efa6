"""dampbound.linear_limits on a stiffness assembled here, in NumPy/SciPy, from a shipped scene's
springs and anchors: the same certified numbers as the scene's own analysis (exact_limits)."""
import numpy as np
import pytest
import scipy.sparse as sp

import dampbound


def assemble_k(arrays):
    """K at rest (SPEC 7): per spring kappa d d^T in [[P, -P], [-P, P]], per anchor kappa_a I."""
    x, springs, kappa = arrays["rest"], arrays["springs"], arrays["stiffness"]
    n = len(x)
    d = x[springs[:, 1]] - x[springs[:, 0]]
    d /= np.linalg.norm(d, axis=1)[:, None]
    P = kappa[:, None, None] * d[:, :, None] * d[:, None, :]
    rows, cols, vals = [], [], []
    for a, b, s in ((0, 0, 1), (1, 1, 1), (0, 1, -1), (1, 0, -1)):
        i, j = springs[:, a], springs[:, b]
        for r in range(3):
            for c in range(3):
                rows.append(3 * i + r)
                cols.append(3 * j + c)
                vals.append(s * P[:, r, c])
    ka = arrays["anchor_stiffness"]
    for r in range(3):
        rows.append(3 * np.arange(n) + r)
        cols.append(3 * np.arange(n) + r)
        vals.append(ka)
    return sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(3 * n, 3 * n)).tocsr()


@pytest.mark.parametrize("dt", [0.05, 0.3])
def test_same_numbers_as_the_scenes_analysis(scenes_dir, dt):
    scene = dampbound.load_scene(str(scenes_dir / "paper-plane.toml"))
    p = scene.params
    p.dt = dt
    a = scene.arrays(p)
    K = assemble_k(a)
    got = dampbound.linear_limits(K, a["mass"], dt=dt, gamma=a["gamma"])
    want = dampbound.exact_limits(scene, p)
    lo, hi = got.lambda_max
    assert hi == pytest.approx(want.lambda_max, rel=1e-12)
    assert lo <= hi
    assert got.dt_max == pytest.approx(want.dt_max, rel=1e-9)
    assert got.gamma_max == pytest.approx(want.gamma_hi, rel=1e-9)
    assert got.stable == want.stable
    # SPEC 9 by hand on the same K: R_i = max over node i's rows of sum |A_rs|.
    m3 = np.repeat(a["mass"], 3)
    A = sp.diags(m3 ** -0.5) @ K @ sp.diags(m3 ** -0.5)
    R = np.abs(A).sum(axis=1).A.ravel().reshape(-1, 3).max(axis=1)
    m = a["mass"]
    assert np.allclose(got.gamma_safe, 2 * m / dt - m * dt * R / 2, rtol=1e-12)
    c = a["gamma"] / m
    assert np.allclose(got.dt_safe, (np.sqrt(c * c + 4 * R) - c) / R, rtol=1e-12)


def test_a_scalar_gamma_and_a_fem_like_matrix():
    # A 1-D chain of 3-D nodes, FEM-like: tridiagonal blocks, both ends held by stiff springs.
    n, k, m = 50, 2.0, 0.01
    main = np.full(n, 2 * k)
    T = sp.diags([-k * np.ones(n - 1), main, -k * np.ones(n - 1)], [-1, 0, 1])
    K = sp.kron(T, sp.identity(3)).tocsc()
    r = dampbound.linear_limits(K, np.full(n, m), dt=0.01, gamma=0.001)
    lam = 4 * k / m * np.sin(np.pi * n / (2 * (n + 1))) ** 2  # the chain's top eigenvalue
    lo, hi = r.lambda_max
    assert lo <= lam * (1 + 1e-12) and hi >= lam * (1 - 1e-12)
    assert hi == pytest.approx(lam, rel=1e-9)
    c = 0.001 / m
    assert r.dt_max == pytest.approx((np.sqrt(c * c + 4 * lam) - c) / lam, rel=1e-9)
    assert r.gamma_max == pytest.approx(2 * m / 0.01 - m * lam * 0.01 / 2, rel=1e-9)


def test_bad_input_names_the_argument():
    K = sp.identity(6, format="csr")
    with pytest.raises(ValueError, match="K: must be 3N x 3N"):
        dampbound.linear_limits(K, [1.0, 1.0, 1.0], dt=0.1)
    with pytest.raises(ValueError, match="mass: node 1"):
        dampbound.linear_limits(K, [1.0, -1.0], dt=0.1)
    bent = K.tolil()
    bent[0, 1] = 0.5
    with pytest.raises(ValueError, match="K: not symmetric"):
        dampbound.linear_limits(bent.tocsr(), [1.0, 1.0], dt=0.1)
    bad = K.tolil()
    bad[2, 2] = np.nan
    with pytest.raises(ValueError, match="not finite"):
        dampbound.linear_limits(bad.tocsr(), [1.0, 1.0], dt=0.1)
    with pytest.raises(ValueError, match="dt"):
        dampbound.linear_limits(K, [1.0, 1.0], dt=0.0)
    with pytest.raises(ValueError, match="gamma: give one value or one per node"):
        dampbound.linear_limits(K, [1.0, 1.0], dt=0.1, gamma=[1.0, 2.0, 3.0])
    with pytest.raises(NotImplementedError, match="C: a damping matrix"):
        dampbound.linear_limits(K, [1.0, 1.0], dt=0.1, C=K)
