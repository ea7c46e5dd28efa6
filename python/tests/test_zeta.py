"""Params.zeta: the nodal damping ratio in place of gamma, resolved at every call that takes
params as the CLI resolves --zeta (gamma_i = zeta * 2 sqrt(m_i kappa_i) at each node)."""
import math

import numpy as np
import pytest

import dampbound


def test_default_is_none_and_repr_says_which():
    p = dampbound.Params()
    assert p.zeta is None
    assert "gamma=" in repr(p)
    p.zeta = 0.5
    assert "zeta=0.5" in repr(p) and "gamma=" not in repr(p)


def test_arrays_gamma_is_zeta_times_the_lower_bound(scenes_dir):
    for name in ("paper-plane", "tissue-block"):
        scene = dampbound.load_scene(str(scenes_dir / f"{name}.toml"))
        p = scene.params
        p.zeta = 0.7
        a = scene.arrays(p)
        lower = 2 * np.sqrt(a["mass"] * a["anchor_stiffness"].clip(min=0))  # anchors only: a floor
        has = ~np.isnan(a["zeta"])
        assert has.any()
        assert np.allclose(a["zeta"][has], 0.7, rtol=1e-12), name
        assert np.all(a["gamma"][has] >= 0.7 * lower[has] * (1 - 1e-12)), name
        p.zeta = None
        plain = scene.arrays(p)
        assert not np.allclose(plain["gamma"], a["gamma"]), name


def test_a_session_with_zeta_runs_as_with_the_gamma_it_means(scenes_dir):
    scene = dampbound.load_scene(str(scenes_dir / "paper-plane.toml"))
    p = scene.params
    p.zeta = 0.5
    by_zeta = dampbound.Session(scene, p).run()
    q = scene.params
    q.gamma = 0.5 * 2 * math.sqrt(q.m * q.kappa)   # uniform plane: every node the same
    by_gamma = dampbound.Session(scene, q).run()
    assert by_zeta.outcome == by_gamma.outcome
    assert by_zeta.iterations == by_gamma.iterations
    assert by_zeta.max_displacement == by_gamma.max_displacement
    lim_z = dampbound.exact_limits(scene, p)
    lim_g = dampbound.exact_limits(scene, q)
    assert lim_z.dt_max == lim_g.dt_max


def test_a_scene_file_with_zeta(tmp_path, scenes_dir):
    text = (scenes_dir / "two-node.toml").read_text()
    lines = [l for l in text.splitlines() if not l.strip().startswith("gamma")]
    out = []
    for l in lines:
        out.append(l)
        if l.strip() == "[params]":
            out.append("zeta = 2.0")
    path = tmp_path / "z.toml"
    path.write_text("\n".join(out) + "\n")
    scene = dampbound.load_scene(str(path))
    assert scene.params.zeta == 2.0
    a = scene.arrays()
    has = ~np.isnan(a["zeta"])
    assert np.allclose(a["zeta"][has], 2.0)
    dampbound.Session(scene).run()


def test_a_bad_zeta_is_a_value_error(scenes_dir):
    scene = dampbound.load_scene(str(scenes_dir / "paper-plane.toml"))
    p = scene.params
    for bad in (-1.0, float("nan"), float("inf")):
        p.zeta = bad
        with pytest.raises(ValueError, match="zeta"):
            dampbound.Session(scene, p)
        with pytest.raises(ValueError, match="zeta"):
            scene.arrays(p)
