"""SPEC 10's damping from Python: Params.kd, rayleigh_mass and rayleigh_stiffness reach the
Session's step (checked against an independent NumPy step on a small sheared square), are
validated with the CLI's words, and move the exact limits as the CLI's do."""
import numpy as np
import pytest

import dampbound

X = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 0.0, 1.0]])
SPRINGS = [(0, 1), (1, 2), (2, 3), (3, 0), (0, 2)]
M, KAPPA, GAMMA, DT = 0.002, 0.003, 0.001, 0.05


def scene_file(tmp_path):
    lines = ['name = "square"']
    for i, x in enumerate(X):
        lines += ["[[node]]", "x = [%r, %r, %r]" % tuple(x), f"fixed = {'true' if i == 0 else 'false'}"]
    for i, j in SPRINGS:
        lines += ["[[spring]]", f"nodes = [{i}, {j}]"]
    lines += ["[params]", f"m = {M}", f"kappa = {KAPPA}", f"gamma = {GAMMA}", f"dt = {DT}",
              'policy = "fixed"', "[[perturb]]", "node = 2", "displacement = [0.1, 0.3, -0.05]",
              "[protocol]", "max_iterations = 100"]
    path = tmp_path / "square.toml"
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def numpy_steps(x, kd, alpha, beta, steps):
    """Semi-implicit Euler with the three damping forces evaluated at the state at t."""
    x = x.copy()
    v = np.zeros_like(x)
    rest = {s: np.linalg.norm(X[s[1]] - X[s[0]]) for s in SPRINGS}
    for _ in range(steps):
        f = -GAMMA * v - alpha * M * v
        for (i, j) in SPRINGS:
            e = x[j] - x[i]
            l = np.linalg.norm(e)
            d = e / l
            l0 = rest[(i, j)]
            f[i] += KAPPA * (l - l0) * d
            f[j] -= KAPPA * (l - l0) * d
            dv = v[j] - v[i]
            f[i] += kd * np.dot(dv, d) * d
            f[j] -= kd * np.dot(dv, d) * d
            B = KAPPA * ((l0 / l) * np.outer(d, d) + (1 - l0 / l) * np.eye(3))
            f[i] += beta * B @ dv
            f[j] -= beta * B @ dv
        f[0] = 0
        v += DT * f / M
        v[0] = 0
        x += DT * v
    return x


@pytest.mark.parametrize("kd,alpha,beta", [(0.004, 0, 0), (0, 0.3, 0), (0, 0, 0.02), (0.004, 0.3, 0.02)])
def test_the_session_steps_as_numpy_does(tmp_path, kd, alpha, beta):
    scene = dampbound.load_scene(scene_file(tmp_path))
    p = scene.params
    p.kd, p.rayleigh_mass, p.rayleigh_stiffness = kd, alpha, beta
    session = dampbound.Session(scene, p)
    start = np.array(session.positions)
    session.step(40)
    ref = numpy_steps(start, kd, alpha, beta, 40)
    assert np.allclose(session.positions, ref, rtol=0, atol=1e-12)
    # and the damping matters: without it the positions differ
    assert not np.allclose(numpy_steps(start, 0, 0, 0, 40), ref, rtol=0, atol=1e-6)


def test_repr_and_validation(tmp_path):
    p = dampbound.Params()
    assert "kd" not in repr(p)
    p.kd = 0.002
    assert "kd=0.002" in repr(p)
    scene = dampbound.load_scene(scene_file(tmp_path))
    for name in ("kd", "rayleigh_mass", "rayleigh_stiffness"):
        q = scene.params
        setattr(q, name, -1.0)
        with pytest.raises(ValueError, match=name):
            dampbound.Session(scene, q)


def test_dashpots_lower_the_exact_dt_limit(scenes_dir):
    scene = dampbound.load_scene(str(scenes_dir / "paper-plane.toml"))
    p = scene.params
    nodal = dampbound.exact_limits(scene, p).dt_max
    p.kd = 0.002
    with_dashpots = dampbound.exact_limits(scene, p).dt_max
    assert nodal == pytest.approx(0.50396164, rel=1e-6)
    assert with_dashpots == pytest.approx(0.11075859, rel=1e-6)  # what `bounds --kd 0.002` says
