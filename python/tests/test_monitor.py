"""The monitor over plain NumPy arrays, checked against the paper's formulas written here in
NumPy and against a dampbound Session on the same model."""
import math

import numpy as np
import pytest

import dampbound


def chain(n=5, k=0.3, m=0.02):
    """n nodes on the x axis, 1 cm apart, springs (i, i+1) with stiffness k*(1 + i/10)."""
    x = np.zeros((n, 3))
    x[:, 0] = np.arange(n, dtype=float)
    springs = np.array([[i, i + 1] for i in range(n - 1)], dtype=np.int64)
    stiffness = k * (1 + np.arange(n - 1) / 10)
    mass = np.full(n, m) * (1 + np.arange(n) / 7)
    return x, springs, stiffness, np.ones(n - 1), mass


def numpy_forces(x, springs, stiffness, rest_length):
    f = np.zeros_like(x)
    d = x[springs[:, 1]] - x[springs[:, 0]]
    length = np.linalg.norm(d, axis=1)
    pull = (stiffness * (length - rest_length) / length)[:, None] * d
    np.add.at(f, springs[:, 0], pull)
    np.add.at(f, springs[:, 1], -pull)
    return f


def test_lower_bounds_are_eq5_with_the_largest_incident_stiffness():
    x, springs, k, l0, m = chain()
    mon = dampbound.Monitor(m, springs, k, l0)
    kmax = np.zeros(len(m))
    for (i, j), ks in zip(springs, k):
        kmax[i] = max(kmax[i], ks)
        kmax[j] = max(kmax[j], ks)
    assert np.allclose(mon.lower_bounds(), 2 * np.sqrt(m * kmax), rtol=1e-15)


def test_forces_and_upper_bounds_match_numpy():
    x, springs, k, l0, m = chain()
    rng = np.random.default_rng(7)
    x = x + 0.1 * rng.standard_normal(x.shape)
    v = rng.standard_normal(x.shape)
    v[2] = 0.0
    mon = dampbound.Monitor(m, springs, k, l0)
    f = mon.internal_forces(x)
    assert np.allclose(f, numpy_forces(x, springs, k, l0), rtol=1e-13, atol=1e-15)
    dt = 0.01
    hi = mon.upper_bounds(v, f, dt)
    speed = np.linalg.norm(v, axis=1)
    expect = np.full(len(m), np.inf)
    moving = speed > 0
    expect[moving] = np.linalg.norm(v * (m / dt)[:, None] + f, axis=1)[moving] / speed[moving]
    assert np.isinf(hi[2])
    assert np.allclose(hi[moving], expect[moving], rtol=1e-14)


def test_strided_views_are_read_in_place_and_give_the_same_numbers():
    x, springs, k, l0, m = chain()
    wide = np.zeros((len(m), 4))
    wide[:, :3] = x + 0.05
    packed = np.ascontiguousarray(wide[:, :3])
    mon = dampbound.Monitor(m, springs, k, l0)
    assert np.array_equal(mon.internal_forces(wide[:, :3]), mon.internal_forces(packed))


def test_check_clamps_into_the_bounds_and_counts_violations():
    x, springs, k, l0, m = chain()
    rng = np.random.default_rng(3)
    x = x + 0.2 * rng.standard_normal(x.shape)
    v = rng.standard_normal(x.shape)
    mon = dampbound.Monitor(m, springs, k, l0)
    f = mon.internal_forces(x)
    dt = 0.01
    lo, hi = mon.lower_bounds(), mon.upper_bounds(v, f, dt)
    gamma = np.zeros(len(m))  # undamped: below every lower bound
    report, g = mon.check(v, f, gamma, dt)
    assert report.violating == int(np.sum((gamma < lo) | (gamma > hi)))
    assert report.first_violating == int(np.argmax((gamma < lo) | (gamma > hi)))
    assert np.array_equal(g, gamma)
    out = np.empty(len(m))
    report, g = mon.check(v, f, gamma, dt, policy="clamp", gamma_eff=out)
    assert g is out or np.shares_memory(g, out)
    ok = lo <= hi
    assert np.array_equal(out[ok], np.clip(gamma, lo, hi)[ok])
    assert np.array_equal(out[~ok], hi[~ok])
    assert report.violating == 0 and report.unstabilisable == int(np.sum(~ok))


def test_bad_input_is_a_value_error_naming_the_entry():
    x, springs, k, l0, m = chain()
    springs[1, 1] = 99
    with pytest.raises(ValueError, match="spring 1"):
        dampbound.Monitor(m, springs, k, l0)
    with pytest.raises(ValueError, match="mass"):
        dampbound.Monitor(-m, springs[:1], k[:1], l0[:1])


def test_exact_limits_of_two_free_nodes():
    # Two masses on one spring: the stretching mode has lambda = 2 kappa/m (SPEC 7).
    m, kappa, dt = 0.5, 2.0, 0.1
    mon = dampbound.Monitor(np.full(2, m), np.array([[0, 1]]), np.array([kappa]), np.ones(1))
    x = np.array([[0.0, 0, 0], [1.0, 0, 0]])
    lim = mon.exact_limits(x, np.full(2, 0.1), dt)
    lam = 2 * kappa / m
    assert lim.lambda_max == pytest.approx(lam, rel=1e-9)
    assert lim.rate_max == pytest.approx(2 / dt - lam * dt / 2, rel=1e-12)
    assert lim.dt_max_undamped == pytest.approx(2 / math.sqrt(lam), rel=1e-9)
    assert lim.stable


def test_exact_limits_of_a_compressed_column_say_no_damping_helps():
    # Two springs pushed to 2/3 of their rest length between fixed ends: in equilibrium, but
    # the sideways stiffness 2 kappa (1 - l0/l) = -kappa is negative (lambda_min = -1), and
    # the column buckles whatever the damping and dt.
    mon = dampbound.Monitor(np.full(3, 0.001), np.array([[0, 1], [1, 2]]), np.full(2, 0.001),
                            np.full(2, 0.75), fixed=np.array([True, False, True]))
    x = np.array([[0.0, 0, 0], [0.5, 0, 0], [1.0, 0, 0]])
    lim = mon.exact_limits(x, np.full(3, 0.002), 0.05)
    assert lim.indefinite and not lim.stable
    assert lim.scale_hi == 0 and lim.dt_max == 0 and lim.rate_max == 0
    assert lim.lambda_max == pytest.approx(2, rel=1e-12)
    stretched = mon.exact_limits(np.array([[0.0, 0, 0], [1.0, 0, 0], [2.0, 0, 0]]),
                                 np.full(3, 0.002), 0.05)
    assert not stretched.indefinite and stretched.stable and stretched.dt_max > 0.05


def test_exact_limits_over_a_factorisation_budget_factorise_nothing():
    scene = dampbound.paper_plane_scene(12)  # 432 rows: the factorisation route
    a = scene.arrays(scene.params)
    mon = dampbound.Monitor(a["mass"], a["springs"], a["stiffness"], a["rest_length"],
                            anchor_stiffness=a["anchor_stiffness"], rest=a["rest"])
    gamma = np.full(len(a["mass"]), 0.002)
    free = mon.exact_limits(a["rest"], gamma, 0.05)
    assert free.computed and free.reason is None and free.lambda_max > 0
    over = mon.exact_limits(a["rest"], gamma, 0.05, factor_budget_gflop=1e-9)
    assert not over.computed and "over the budget" in over.reason
    assert math.isnan(over.lambda_max) and math.isnan(over.dt_max)
    assert math.isnan(free.dt_unstable_from)
    assert over.lambda_max_at_least <= free.lambda_max
    assert free.scale_hi <= over.scale_unstable_from < 1.001 * free.scale_hi
    assert free.dt_max <= over.dt_unstable_from < 1.001 * free.dt_max
    # The stable side, proved by Gershgorin on the index matrix (SPEC 9): no spring is
    # compressed at rest.
    assert over.stable and math.isnan(free.scale_stable_up_to)
    assert 1 <= over.scale_stable_up_to <= free.scale_hi
    assert 0.05 <= over.dt_stable_up_to <= free.dt_max
    assert mon.exact_limits(a["rest"], gamma, 0.05, factor_budget_gflop=1e3).dt_max == free.dt_max
    with pytest.raises(ValueError, match="factor_budget_gflop"):
        mon.exact_limits(a["rest"], gamma, 0.05, factor_budget_gflop=0.0)


def test_monitor_reproduces_a_sessions_bounds_bit_for_bit():
    # The same model through the monitor (state read from the session before a step) and
    # through the session's own step(): equal upper bounds and effective damping.
    scene = dampbound.paper_plane_scene(6)
    p = scene.params
    p.policy = "clamp"
    p.gamma = 0.0005
    session = dampbound.Session(scene, p)
    a = scene.arrays(p)
    mon = dampbound.Monitor(a["mass"], a["springs"], a["stiffness"], a["rest_length"],
                            anchor_stiffness=a["anchor_stiffness"], rest=a["rest"])
    assert np.array_equal(mon.lower_bounds(), session.lower_bounds)
    for _ in range(5):
        x, v = session.positions.copy(), session.velocities.copy()
        f = mon.internal_forces(x)
        report, g = mon.check(v, f, a["gamma"], p.dt, policy="clamp")
        stats = session.step()
        assert np.array_equal(mon.upper_bounds(v, f, p.dt), session.upper_bounds)
        assert np.array_equal(g, session.gamma_eff)
        assert report.violating == stats.violating
        assert report.unstabilisable == stats.unstabilisable
        assert report.clamped == stats.clamped


def test_monitor_safe_policy_matches_the_sessions_step():
    # SPEC 9 through the monitor with the positions at t: the same effective damping as the
    # session's step() under policy safe, bit for bit, and an absurd gamma cut down to the bound.
    scene = dampbound.paper_plane_scene(6)
    p = scene.params
    p.policy = "safe"
    p.gamma = 1.0
    session = dampbound.Session(scene, p)
    a = scene.arrays(p)
    mon = dampbound.Monitor(a["mass"], a["springs"], a["stiffness"], a["rest_length"],
                            anchor_stiffness=a["anchor_stiffness"], rest=a["rest"])
    for _ in range(4):
        x, v = session.positions.copy(), session.velocities.copy()
        f = mon.internal_forces(x)
        safe = mon.safe_bounds(x, p.dt)
        report, g = mon.check(v, f, a["gamma"], p.dt, policy="safe", x=x)
        stats = session.step()
        assert np.array_equal(g, session.gamma_eff)
        assert np.all(g <= safe) and np.all(g < 1.0)
        assert report.clamped == stats.clamped
    with pytest.raises(ValueError, match="positions"):
        mon.check(v, f, a["gamma"], p.dt, policy="safe")


def test_monitor_threads_give_the_same_bits():
    # A 40 000-node plane in a random state (its loops split from 2 threads on): every output
    # on 2 threads equals the one-thread one; a negative count is refused.
    scene = dampbound.paper_plane_scene(200)
    p = scene.params
    a = scene.arrays(p)
    mon = dampbound.Monitor(a["mass"], a["springs"], a["stiffness"], a["rest_length"],
                            anchor_stiffness=a["anchor_stiffness"], rest=a["rest"])
    rng = np.random.default_rng(3)
    x = a["rest"] + 0.2 * rng.uniform(-1, 1, a["rest"].shape)
    v = 5 * rng.uniform(-1, 1, a["rest"].shape)
    gamma = 3 * a["mass"] / p.dt
    assert mon.threads == 1

    def outputs():
        f = mon.internal_forces(x)
        report, g = mon.check(v, f, gamma, p.dt, policy="safe", x=x)
        return f, mon.safe_bounds(x, p.dt), g, mon.upper_bounds(v, f, p.dt), report

    f1, s1, g1, u1, r1 = outputs()
    mon.threads = 2
    assert mon.threads == 2
    f2, s2, g2, u2, r2 = outputs()
    assert np.array_equal(f1, f2) and np.array_equal(s1, s2)
    assert np.array_equal(g1, g2) and np.array_equal(u1, u2)
    assert (r1.violating, r1.clamped, r1.first_violating) == (r2.violating, r2.clamped,
                                                              r2.first_violating)
    assert r1.violating > 0
    with pytest.raises(ValueError, match="threads"):
        mon.threads = -1


def test_results_read_first_as_their_answer():
    # Each repr says the verdict first, in the words the CLI uses, and agrees with the fields.
    m, kappa = 0.5, 2.0
    mon = dampbound.Monitor(np.full(2, m), np.array([[0, 1]]), np.array([kappa]), np.ones(1))
    x = np.array([[0.0, 0, 0], [1.0, 0, 0]])
    stable = mon.exact_limits(x, np.full(2, 0.1), 0.1)
    assert stable.stable and repr(stable).startswith("MonitorLimits(stable at these gamma_i")
    unstable = mon.exact_limits(x, np.full(2, 0.1), 3.0)  # dt above 2/sqrt(lambda) = 1
    assert not unstable.stable and repr(unstable).startswith("MonitorLimits(NOT stable")
    over = mon.exact_limits(x, np.full(2, 0.1), 0.1, factor_budget_gflop=1e-12)
    if not over.computed:
        assert repr(over) == "MonitorLimits(not computed: " + over.reason + ")"
    v = np.array([[0.0, 0, 0], [1.0, 0, 0]])
    f = mon.internal_forces(x)
    report, _ = mon.check(v, f, np.zeros(2), 0.1)  # undamped: below gamma_lo at both nodes
    assert not report.ok and repr(report).startswith("MonitorReport(NOT ok: 2 nodes outside")
    report, _ = mon.check(v, f, mon.lower_bounds(), 0.1)
    assert report.ok and repr(report).startswith("MonitorReport(ok:")


def test_suggest_reads_first_as_the_clis_answer(scenes_dir):
    scene = dampbound.load_scene(str(scenes_dir / "two-node.toml"))
    s = dampbound.suggest(scene, verify=False)
    assert isinstance(s, dict) and isinstance(s, dampbound.Suggestion)
    assert repr(s) == "Suggestion(" + s["answer"] + ")"
    assert s["answer"] and "gamma" in s["answer"]
    t = dampbound.suggest(scene, what="dt", verify=False)
    assert repr(t) == "Suggestion(" + t["answer"] + ")" and "dt" in t["answer"]
    assert dict(t)["dt_exact"] == t["dt_exact"]  # still a plain dict of the numbers
