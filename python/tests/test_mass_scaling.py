"""dampbound.mass_scaling (SPEC 11) on a scene and on matrices assembled here in NumPy/SciPy:
the same masses both ways, stable at the design step by a dense eigenvalue computed here."""
import numpy as np
import pytest
import scipy.sparse as sp

import dampbound

from test_linear_limits import assemble_k

PLANE = """
[grid]
nx = 8
nz = 8
spacing = 0.57
[[region]]
min = [1.7, -1.0, 1.7]
max = [2.3, 1.0, 2.3]
mass_scale = 0.1
[[region]]
min = [0.0, 0.0, 0.0]
max = [0.0, 0.0, 0.0]
fixed = true
[params]
m = 0.001
kappa = 0.001
gamma = 0.002
[[perturb]]
node = [4, 4]
displacement = [0.0, 5.0, 0.0]
"""


@pytest.fixture
def plane(tmp_path):
    path = tmp_path / "plane.toml"
    path.write_text(PLANE)
    return dampbound.load_scene(str(path))


def index(K, C, mass, h, alpha=0.0):
    """lambda_max(h^2 A + 2 h C^) (SPEC 10), dense."""
    w = np.repeat(mass, 3) ** -0.5
    S = (h * h * K.toarray() + 2 * h * C.toarray()) * w[:, None] * w[None, :]
    return np.linalg.eigvalsh(S).max() + 2 * h * alpha


def test_scene_spec_eleven_plane(plane):
    r = dampbound.mass_scaling(plane, 0.3)
    assert r["answer"] == "scaled"
    assert r["scaled_nodes"] == 4
    assert r["added_local_percent"] == pytest.approx(3.2548, abs=1e-3)
    assert r["added_percent"] == pytest.approx(2.7716, abs=1e-3)
    assert r["s_star"] == pytest.approx(0.8515625)
    assert r["verified"] is True
    m, m0 = r["mass"], r["mass_before"]
    assert isinstance(m, np.ndarray) and m.shape == (64,)
    assert m[0] == m0[0]  # the fixed node
    assert np.count_nonzero(m > m0) == 4
    assert len(r["top"]) == 4 and "mass 10x below" in r["top"][0]["cause"]
    assert r["scene"].params.dt == 0.3


def test_matrices_give_the_scenes_masses_and_are_stable_at_the_design_step(plane):
    a = plane.arrays()
    free = np.flatnonzero(a["fixed"] == 0)
    dofs = (3 * free[:, None] + np.arange(3)).ravel()
    K = assemble_k(a)[dofs][:, dofs]
    mass = a["mass"][free]
    got = dampbound.mass_scaling(K, mass, dt=0.3, gamma=0.002)
    want = dampbound.mass_scaling(plane, 0.3, verify=False)
    assert got["answer"] == "scaled" and got["scaled_nodes"] == 4
    assert got["s_star"] == want["s_star"]
    np.testing.assert_allclose(got["mass"], want["mass"][free], rtol=1e-12)
    C = 0.002 * sp.identity(3 * len(free))
    h = 0.3 / 0.9
    assert index(K, C, mass, h) >= 4
    assert index(K, C, got["mass"], h) < 4
    assert index(K, C, got["mass_local"], h) < 4
    # The local rule by hand: node i's largest absolute row sum of N over 4.
    N = abs(2 * h * C + h * h * K)
    req = np.asarray(N.sum(axis=1)).ravel().reshape(-1, 3).max(axis=1) / 4
    local = np.where(mass <= req, req * (1 + 1e-6), mass)
    np.testing.assert_allclose(got["mass_local"], local, rtol=1e-12)


def test_matrices_with_dashpots_and_rayleigh_mass_damping(plane):
    a = plane.arrays()
    free = np.flatnonzero(a["fixed"] == 0)
    dofs = (3 * free[:, None] + np.arange(3)).ravel()
    K = assemble_k(a)[dofs][:, dofs]
    mass = a["mass"][free]
    C = 0.1 * K  # stiffness-proportional: does not scale with the masses
    r = dampbound.mass_scaling(K, mass, dt=0.3, gamma=0.002, C=C, rayleigh_mass=0.2)
    assert r["answer"] == "scaled" and not r["over_cap"]
    Cp = C + 0.002 * sp.identity(3 * len(free))
    h = 0.3 / 0.9
    assert index(K, Cp, r["mass"], h, alpha=0.2) < 4
    assert index(K, Cp, mass, h, alpha=0.2) >= 4
    assert r["added_percent"] == pytest.approx(3.664, abs=1e-3)  # beta = 0.1 s: within 5 %
    over = dampbound.mass_scaling(K, mass, dt=0.3, gamma=0.002, C=3 * C, rayleigh_mass=0.2)
    assert over["over_cap"] and over["added_percent"] > 5 and 0 < over["dt_cap"] < 0.3
    assert over["mass"].shape == mass.shape
    none = dampbound.mass_scaling(K, mass, dt=0.3, rayleigh_mass=20.0)
    assert none["answer"] == "no_mass_helps"
    assert none["dt_no_mass"] == pytest.approx(2 * 0.9 / 20)
    assert dampbound.mass_scaling(K, mass, dt=0.01, gamma=0.002)["answer"] == "nothing_to_add"


def test_bad_input_names_the_argument(plane):
    K = sp.identity(6, format="csr")
    with pytest.raises(ValueError, match="K: must be 3N x 3N"):
        dampbound.mass_scaling(K, [1.0, 1.0, 1.0], dt=0.1)
    with pytest.raises(ValueError, match="safety"):
        dampbound.mass_scaling(K, [1.0, 1.0], dt=0.1, safety=2.0)
    with pytest.raises(ValueError, match="rayleigh_mass"):
        dampbound.mass_scaling(K, [1.0, 1.0], dt=0.1, rayleigh_mass=-1.0)
    with pytest.raises(ValueError, match="target"):
        dampbound.mass_scaling(plane, -0.3)
