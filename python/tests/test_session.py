"""The module's scene and session: NumPy views, the protocol result, the bounds."""
import locale
import math

import numpy as np
import pytest

import dampbound


def test_version_is_the_packages():
    parts = dampbound.__version__.split(".")
    assert len(parts) == 3 and all(p.isdigit() for p in parts)


def test_bad_scene_file_names_the_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("name = 'x'\n[params]\nm = -1\n")
    with pytest.raises(ValueError, match="bad.toml"):
        dampbound.load_scene(str(bad))


def test_two_node_at_critical_damping_settles(scenes_dir):
    # The paper's sec. 2 system at gamma = 2 sqrt(m kappa): critically damped, it settles,
    # judged by the settled rule as `dampbound run` judges it.
    scene = dampbound.load_scene(str(scenes_dir / "two-node.toml"))
    result = dampbound.Session(scene).run()
    assert result.outcome == "settled"
    assert result.iterations == scene.rules.max_iterations
    assert 0 < result.settled_at < scene.rules.max_iterations
    assert result.left_at is None
    assert result.violations == 0


def test_positions_are_views_of_the_session():
    session = dampbound.Session(dampbound.paper_plane_scene(6))
    x = session.positions
    assert x.shape == (36, 3) and x.dtype == np.float64
    assert not x.flags.writeable
    before = x.copy()
    session.step(3)
    # The same memory, now holding the state after three steps.
    assert x.__array_interface__["data"][0] == session.positions.__array_interface__["data"][0]
    assert not np.array_equal(x, before)
    assert session.iteration == 3
    assert session.time == pytest.approx(3 * session.params.dt)
    assert session.velocities.shape == (36, 3)


def test_bounds_match_the_paper_equations():
    scene = dampbound.paper_plane_scene(6)
    session = dampbound.Session(scene)
    p = session.params
    # eq. 5 with uniform stiffness: 2 sqrt(m kappa) at every node.
    assert np.allclose(session.lower_bounds, 2 * math.sqrt(p.m * p.kappa), rtol=1e-15)
    session.step()
    v_before = session.velocities.copy()
    hi = session.upper_bounds  # eq. 6 at t = 0, where every velocity is 0
    assert np.all(np.isinf(hi))
    session.step()
    assert np.all(np.isfinite(session.upper_bounds[np.linalg.norm(v_before, axis=1) > 0]))


def test_params_round_trip_and_reject_unknown_policy():
    p = dampbound.Params()
    p.policy = "clamp"
    p.gamma = 0.0
    assert p.policy == "clamp"
    with pytest.raises(ValueError):
        p.policy = "sometimes"


def test_exact_limits_and_suggest_agree_on_the_two_node_system(scenes_dir):
    scene = dampbound.load_scene(str(scenes_dir / "two-node.toml"))
    p = scene.params
    e = dampbound.exact_limits(scene)
    # One free node on one spring: lambda_max = kappa/m along the spring (SPEC 7).
    assert e.lambda_max == pytest.approx(p.kappa / p.m, rel=1e-9)
    # gamma < 2m/dt - m lambda dt/2 (SPEC 7).
    assert e.gamma_hi == pytest.approx(2 * p.m / p.dt - p.m * e.lambda_max * p.dt / 2, rel=1e-9)
    s = dampbound.suggest(scene, verify=False)
    assert s["gamma_min"] <= s["gamma_best"] < s["gamma_max"] <= e.gamma_hi * (1 + 1e-12)
    t = dampbound.suggest(scene, what="dt", verify=True)
    assert 0 < t["dt_all"] <= t["dt_exact"]
    for params, result in t["runs"].values():
        assert result.outcome != "diverged"


def test_suggest_over_a_factorisation_budget_suggests_what_is_proved(scenes_dir):
    scene = dampbound.load_scene(str(scenes_dir / "paper-plane.toml"))
    exact = dampbound.suggest(scene, verify=False)
    over = dampbound.suggest(scene, verify=False, factor_budget_gflop=1e-9)
    assert not exact["proved_only"] and over["proved_only"]
    assert over["gamma_min"] == exact["gamma_min"]
    assert over["gamma_max"] < exact["gamma_max"] <= over["gamma_unstable_from"]
    t = dampbound.suggest(scene, what="dt", verify=False, factor_budget_gflop=1e-9)
    e = dampbound.exact_limits(scene)
    assert t["proved_only"] and t["dt_exact"] < e.dt_max <= t["dt_unstable_from"]
    with pytest.raises(ValueError, match="factor_budget_gflop"):
        dampbound.suggest(scene, verify=False, factor_budget_gflop=0)


def test_static_equilibrium_of_a_loaded_chain_and_the_limits_there(tmp_path):
    # Eleven springs between fixed ends, every free node pulled down: slack at rest.
    lines = ['name = "chain"']
    for i in range(12):
        lines += ["[[node]]", f"x = [{0.5 * i}, 0.0, 0.0]"]
        lines += ["fixed = true"] if i in (0, 11) else ["force = [0.0, -0.0005, 0.0]"]
    for i in range(11):
        lines += ["[[spring]]", f"nodes = [{i}, {i + 1}]"]
    (tmp_path / "chain.toml").write_text("\n".join(lines) + "\n")
    scene = dampbound.load_scene(str(tmp_path / "chain.toml"))
    eq = dampbound.static_equilibrium(scene)
    assert eq["converged"] and eq["iterations"] > 1
    assert eq["net_force"] <= 1e-10 * eq["force_scale"]
    assert eq["x"].shape == (12, 3) and eq["x"][6, 1] < -0.1  # it sags
    rest = dampbound.exact_limits(scene)
    there = dampbound.exact_limits(scene, x=eq["x"])
    assert there.lambda_max == pytest.approx(3.7151536, rel=1e-7)  # 3.9189859 at rest
    assert rest.lambda_max == pytest.approx(3.9189859, rel=1e-7)
    with pytest.raises(ValueError, match="one row per node"):
        dampbound.exact_limits(scene, x=eq["x"][:5])


def test_exact_limits_take_a_thread_count_and_give_the_same_numbers(scenes_dir):
    scene = dampbound.load_scene(str(scenes_dir / "paper-plane.toml"))
    one = dampbound.exact_limits(scene)
    every_cpu = dampbound.exact_limits(scene, threads=0)
    assert (one.lambda_max, one.gamma_hi, one.dt_max) == (
        every_cpu.lambda_max, every_cpu.gamma_hi, every_cpu.dt_max)
    with pytest.raises(ValueError, match="threads"):
        dampbound.exact_limits(scene, threads=-1)


def test_exact_limits_over_a_factorisation_budget_factorise_nothing(scenes_dir):
    scene = dampbound.load_scene(str(scenes_dir / "paper-plane.toml"))
    free = dampbound.exact_limits(scene)
    assert free.computed and free.reason is None
    over = dampbound.exact_limits(scene, factor_budget_gflop=1e-9)
    assert not over.computed
    assert "over the budget of 1e-09 GFlop" in over.reason
    assert math.isnan(over.dt_max) and math.isnan(over.lambda_max)
    assert free.unfactored is None
    # Without a factorisation, Lanczos and Gershgorin still bracket lambda_max, and the dt
    # and gamma from which the step is proved unstable lie at or past the exact limits.
    b = over.unfactored
    assert b.lambda_max_lo <= free.lambda_max <= b.lambda_max_hi
    assert free.dt_max <= b.dt_unstable_from < 1.001 * free.dt_max
    assert free.gamma_hi <= b.gamma_unstable_from < 1.001 * free.gamma_hi
    assert b.index_at_least < 4 and 0 < b.lanczos_steps <= 40 and not b.unconditional
    # ... and Gershgorin on the index matrix (SPEC 9's safe bound) proves the stable side.
    assert over.stable and b.index_at_least <= b.index_at_most < 4
    assert b.gamma_stable_lo == 0 and scene.params.gamma <= b.gamma_stable_hi <= free.gamma_hi
    assert scene.params.dt <= b.dt_stable_up_to <= free.dt_max
    assert math.isnan(b.mode_unstable_from) and math.isnan(b.gamma_unstable_below)
    # Forward Euler (uniform gamma/m): its per-mode closed form, on the unstable side.
    params = scene.params  # a copy: set it back
    params.integrator = "forward-euler"
    scene.params = params
    fe_free = dampbound.exact_limits(scene)
    fe = dampbound.exact_limits(scene, factor_budget_gflop=1e-9).unfactored
    assert fe_free.dt_max <= fe.dt_unstable_from < 1.001 * fe_free.dt_max
    assert 0.999 * fe_free.gamma_lo < fe.gamma_unstable_below <= fe_free.gamma_lo
    assert fe.mode_unstable_from > fe.lambda_max_lo  # the scene's dt is not proved unstable
    # ... and K >= 0 at rest with Gershgorin's bound proves it stable.
    assert fe.stable_lambda_hi >= fe_free.lambda_max
    assert 0 < fe.dt_stable_up_to <= fe_free.dt_max
    assert fe_free.gamma_lo <= fe.gamma_stable_lo <= params.gamma <= fe.gamma_stable_hi <= fe_free.gamma_hi
    # RK4: proved stable at the scene's gamma and dt, every dt up to a bound and every
    # gamma in a range around the scene's.
    params.integrator = "rk4"
    scene.params = params
    rk4_free = dampbound.exact_limits(scene)
    rk4 = dampbound.exact_limits(scene, factor_budget_gflop=1e-9)
    assert rk4.stable and rk4.unfactored.stable_lambda_hi >= rk4_free.lambda_max
    assert params.dt < rk4.unfactored.dt_stable_up_to <= rk4_free.dt_max
    assert rk4_free.gamma_lo <= rk4.unfactored.gamma_stable_lo <= params.gamma
    assert params.gamma <= rk4.unfactored.gamma_stable_hi <= rk4_free.gamma_hi
    params.integrator = "semi-implicit-euler"
    scene.params = params
    roomy = dampbound.exact_limits(scene, factor_budget_gflop=200.0)
    assert (roomy.lambda_max, roomy.gamma_hi, roomy.dt_max) == (
        free.lambda_max, free.gamma_hi, free.dt_max)
    for bad in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="factor_budget_gflop"):
            dampbound.exact_limits(scene, factor_budget_gflop=bad)


def test_over_the_budget_a_patch_pins_the_tissue_blocks_limits(scenes_dir):
    # The tissue block's index has its top at a light corner: under a budget that the sparse
    # factorisation (6.75 GFlop) exceeds and the 90-node patch (0.0066 GFlop) does not, the
    # paper step's gamma and dt limits are proved from both sides, 1e-10 apart, around the
    # factorised ones (which err low by up to the certified interval's width).
    scene = dampbound.load_scene(str(scenes_dir / "tissue-block.toml"))
    b = dampbound.exact_limits(scene, factor_budget_gflop=0.01).unfactored
    assert b.patch_nodes == 90 and b.index_patch == b.index_at_most
    assert b.index_at_least <= b.index_at_most < b.index_at_least * (1 + 1e-10)
    free = dampbound.exact_limits(scene)
    for stable, unstable, exact in ((b.gamma_stable_hi, b.gamma_unstable_from, free.gamma_hi),
                                    (b.dt_stable_up_to, b.dt_unstable_from, free.dt_max)):
        assert stable <= unstable < stable * (1 + 1e-10)
        assert stable * (1 - 1e-8) < exact <= unstable
    # Under a budget the patch exceeds too, the node-by-node bounds alone: 2.5 % wide.
    g = dampbound.exact_limits(scene, factor_budget_gflop=0.001).unfactored
    assert g.patch_nodes == 0 and math.isnan(g.index_patch)
    assert g.gamma_stable_hi < 0.98 * free.gamma_hi


def test_settled_rule_runs_to_the_limit_and_reports_the_first_entry(scenes_dir):
    scene = dampbound.load_scene(str(scenes_dir / "two-node.toml"))
    rules = scene.rules
    rules.rule = "first-entry"  # the paper's rule, asked for
    rules.max_iterations = 400
    first = dampbound.Session(scene, rules=rules).run()
    assert first.outcome == "restored" and first.settled_at is None
    rules.rule = "settled"
    settled = dampbound.Session(scene, rules=rules).run()
    assert settled.outcome == "settled" and settled.iterations == 400
    assert settled.first_entry == first.iterations
    assert 0 < settled.settled_at <= 400


def test_one_default_rule_settled_everywhere(scenes_dir):
    # The CLI's default (SPEC 8): a new StopRules, a scene's rules and a Session without rules
    # all judge by the settled rule; first-entry only when asked for.
    assert dampbound.StopRules().rule == "settled"
    scene = dampbound.load_scene(str(scenes_dir / "two-node.toml"))
    assert scene.rules.rule == "settled"
    rules = dampbound.StopRules()
    rules.reference = scene.rules.reference
    rules.max_iterations = 400
    r = dampbound.Session(scene, rules=rules).run()
    assert r.outcome == "settled" and r.iterations == 400


def test_a_comma_locale_leaves_mesh_scenes_readable(scenes_dir):
    # A script that calls locale.setlocale(LC_ALL, "") in Germany gives the C library a
    # decimal comma; dampbound's mesh readers and writers keep the point.
    before = locale.setlocale(locale.LC_NUMERIC)
    try:
        locale.setlocale(locale.LC_NUMERIC, "de_DE.UTF-8")  # scripts/install-deps.sh makes it
        assert locale.localeconv()["decimal_point"] == ","
        scene = dampbound.load_scene(str(scenes_dir / "tissue-cap.toml"))
        assert scene.node_count == 433
        result = dampbound.Session(scene).run()
        assert result.iterations > 0
        p = dampbound.Params()
        p.dt = 1e-9
        assert repr(p).startswith("Params(m=0.001, kappa=0.001, gamma=0.002, dt=1e-09,")
    finally:
        locale.setlocale(locale.LC_NUMERIC, before)
