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
    with pytest.raises(ValueError, match="C: must be 3N x 3N"):
        dampbound.linear_limits(K, [1.0, 1.0], dt=0.1, C=sp.identity(3))
    with pytest.raises(ValueError, match="C: not symmetric"):
        dampbound.linear_limits(K, [1.0, 1.0], dt=0.1, C=bent.tocsr())


def dashpot_chain(n=6, seed=7):
    """A bent chain of n nodes with springs (kappa) and dashpots (kd) along them, anchored at
    both ends: K, the dashpot matrix D (same pattern, kd instead of kappa) and the masses."""
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.uniform(0.5, 1.5, (n, 3)), axis=0)
    kappa = rng.uniform(0.5, 2.0, n - 1)
    kd = rng.uniform(0.01, 0.2, n - 1)
    m = rng.uniform(0.5, 2.0, n)
    K = np.zeros((3 * n, 3 * n))
    D = np.zeros((3 * n, 3 * n))
    for s in range(n - 1):
        d = x[s + 1] - x[s]
        d /= np.linalg.norm(d)
        P = np.outer(d, d)
        for M, c in ((K, kappa[s]), (D, kd[s])):
            for a, b, sign in ((s, s, 1), (s + 1, s + 1, 1), (s, s + 1, -1), (s + 1, s, -1)):
                M[3 * a:3 * a + 3, 3 * b:3 * b + 3] += sign * c * P
    for end in (0, n - 1):
        K[3 * end:3 * end + 3, 3 * end:3 * end + 3] += 1.5 * np.eye(3)
    return K, D, m


def amplification_radius(K, C, m, dt):
    """Spectral radius of the paper's step (semi-implicit Euler) on x' = v, M v' = -K x - C v."""
    n3 = len(K)
    Minv = np.diag(1.0 / np.repeat(m, 3))
    V = np.eye(n3) - dt * Minv @ C          # v' = V v + W x
    W = -dt * Minv @ K
    T = np.block([[np.eye(n3) + dt * W, dt * V], [W, V]])
    return max(abs(np.linalg.eigvals(T)))


@pytest.mark.parametrize("alpha, beta", [(0.0, 0.0), (0.05, 0.01)])
def test_a_damping_matrix_against_dense_references(alpha, beta):
    K, D, m = dashpot_chain()
    m3 = np.repeat(m, 3)
    C = D + alpha * np.diag(m3) + beta * K   # dashpots and Rayleigh damping (SPEC 10)
    gamma = 0.02 * m                         # nodal damping beside C
    dt = 0.3
    got = dampbound.linear_limits(sp.csr_matrix(K), m, dt=dt, gamma=gamma, C=sp.csr_matrix(C))
    assert got.damping_matrix
    W = np.diag(m3 ** -0.5)
    A = W @ K @ W
    Ch = W @ (np.diag(np.repeat(gamma, 3)) + C) @ W

    def index(h):
        return max(np.linalg.eigvalsh(h * h * A + 2 * h * Ch))

    assert got.index == pytest.approx(index(dt), rel=1e-9)
    assert got.damping_min == pytest.approx(min(np.linalg.eigvalsh(Ch)), rel=1e-9, abs=1e-12)
    assert got.stable == (index(dt) < 4)
    # dt_max: the index crosses 4 there, and the step's own amplification matrix agrees.
    h = got.dt_max
    assert index(h * (1 - 1e-7)) < 4 < index(h * (1 + 1e-7))
    assert amplification_radius(K, C + np.diag(np.repeat(gamma, 3)), m, h * (1 - 1e-6)) <= 1 + 1e-9
    assert amplification_radius(K, C + np.diag(np.repeat(gamma, 3)), m, h * (1 + 1e-4)) > 1
    # gamma_max scales the nodal pattern (gamma / max gamma), C held.
    g = got.gamma_max * gamma / gamma.max()
    Chg = lambda f: W @ (np.diag(np.repeat(f * g, 3)) + C) @ W
    assert max(np.linalg.eigvalsh(dt * dt * A + 2 * dt * Chg(1 - 1e-7))) < 4
    assert max(np.linalg.eigvalsh(dt * dt * A + 2 * dt * Chg(1 + 1e-6))) > 4
    # The generalised safe bound (SPEC 10): Gershgorin on 4 I - 2 dt C^ - dt^2 A, nodal part
    # left out, m_i / (2 dt) times node i's smallest margin.
    Cp = W @ C @ W
    Q = 2 * dt * Cp + dt * dt * A
    margin = 4 - np.diag(Q) - (np.abs(Q).sum(axis=1) - np.abs(np.diag(Q)))
    want = m / (2 * dt) * margin.reshape(-1, 3).min(axis=1)
    assert np.allclose(got.gamma_safe, want, rtol=1e-12, atol=1e-12)
    # dt_safe_i: node i's margins with its own gamma_i close there and not before.
    for i, t in enumerate(got.dt_safe):
        def node_margin(h):
            Qh = 2 * h * (Cp + np.diag(np.repeat(gamma / m, 3))) + h * h * A
            rows = slice(3 * i, 3 * i + 3)
            mg = 4 - np.diag(Qh) - (np.abs(Qh).sum(axis=1) - np.abs(np.diag(Qh)))
            return mg[rows].min()
        assert node_margin(t * (1 - 1e-9)) > 0
        assert node_margin(t * (1 + 1e-6)) < 0


def test_without_c_the_numbers_do_not_move():
    K, D, m = dashpot_chain()
    a = dampbound.linear_limits(sp.csr_matrix(K), m, dt=0.3, gamma=0.02)
    assert not a.damping_matrix
    b = dampbound.linear_limits(sp.csr_matrix(K), m, dt=0.3, gamma=0.02, C=sp.csr_matrix(K.shape))
    # An all-zero C: the same dt limit by the index as by SPEC 7's closed forms.
    assert b.damping_matrix
    assert b.dt_max == pytest.approx(a.dt_max, rel=1e-8)
    assert b.gamma_max == pytest.approx(a.gamma_max, rel=1e-8)
