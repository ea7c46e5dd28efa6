"""The bad-input battery of the Python module, parameters: every door that takes parameters,
stop rules, a model size, a path, a budget or threads, and the GIL. Each case asserts the
exception type (docs/embedding.md, "Bad input")."""
import math
import threading
import time

import numpy as np
import pytest

import dampbound as d

NAN, INF = math.nan, math.inf
N = 16  # paper_plane_scene(4)



@pytest.fixture(scope="module")
def arrays():
    return d.paper_plane_scene(4).arrays()


# --- parameters at every door --------------------------------------------------------------

BAD_PARAMS = [("m", 0.0), ("m", -1.0), ("m", NAN), ("m", INF), ("kappa", 0.0), ("kappa", NAN),
              ("gamma", -1.0), ("gamma", NAN), ("gamma", INF), ("dt", 0.0), ("dt", -0.05),
              ("dt", NAN), ("dt", INF), ("factor", -1.0), ("factor", NAN)]


def bad_params(name, value):
    p = d.Params()
    setattr(p, name, value)
    return p


DOORS = {
    "Session": lambda sc, p: d.Session(sc, p),
    "exact_limits": lambda sc, p: d.exact_limits(sc, p),
    "static_equilibrium": lambda sc, p: d.static_equilibrium(sc, p),
    "suggest": lambda sc, p: d.suggest(sc, p, verify=False),
    "Scene.arrays": lambda sc, p: sc.arrays(p),
}


@pytest.mark.parametrize("door", sorted(DOORS))
@pytest.mark.parametrize("name,value", BAD_PARAMS)
def test_bad_parameters_are_refused_at_every_door(door, name, value):
    with pytest.raises(ValueError, match=rf"^{name} must be"):
        DOORS[door](d.paper_plane_scene(3), bad_params(name, value))


def test_set_params_is_validated():
    s = d.Session(d.paper_plane_scene(3))
    with pytest.raises(ValueError, match="dt must be > 0"):
        s.params = bad_params("dt", 0.0)


@pytest.mark.parametrize("name,value,words", [
    ("max_iterations", -5, "max_iterations must be in 1..100000000"),
    ("max_iterations", 0, "max_iterations must be in 1..100000000"),
    ("restore_fraction", NAN, "restore_fraction must be finite"),
    ("diverge_factor", 0.0, "diverge_factor must be > 0"),
    ("reference", -1.0, "reference must be > 0"),
])
@pytest.mark.parametrize("door", ["Session", "suggest"])
def test_bad_stop_rules_are_refused(door, name, value, words):
    sc = d.paper_plane_scene(3)
    r = d.StopRules()
    setattr(r, name, value)
    with pytest.raises(ValueError, match=words):
        if door == "Session":
            d.Session(sc, None, r)
        else:
            d.suggest(sc, None, r, verify=False)


@pytest.mark.parametrize("n", [0, -1, 2001])
def test_an_empty_or_oversized_plane_is_refused_not_crashed(n):
    with pytest.raises(ValueError, match="n must be in 1..2000"):
        d.paper_plane_scene(n)


def test_a_one_node_session_runs():
    assert d.Session(d.paper_plane_scene(1)).step().iteration == 1


@pytest.mark.parametrize("suffix", ["\0", "\0.bak", "\0/../x"])
def test_a_path_with_a_nul_is_refused(scenes_dir, suffix):
    with pytest.raises(ValueError, match="NUL"):
        d.load_scene(str(scenes_dir / "paper-plane.toml") + suffix)


@pytest.mark.parametrize("budget", [0.0, -1.0, NAN, INF])
def test_a_bad_budget_is_refused(budget):
    with pytest.raises(ValueError, match="factor_budget_gflop"):
        d.exact_limits(d.paper_plane_scene(3), factor_budget_gflop=budget)


@pytest.mark.parametrize("threads", [-1, -100])
def test_negative_threads_are_refused(threads):
    with pytest.raises(ValueError, match="threads"):
        d.exact_limits(d.paper_plane_scene(3), threads=threads)


@pytest.mark.parametrize("bad", [NAN, INF])
def test_exact_limits_of_a_scene_at_non_finite_positions_is_an_error(bad):
    sc = d.paper_plane_scene(3)
    x = np.array(sc.rest)
    x[4, 2] = bad
    with pytest.raises(ValueError, match=r"x\[4\] is not finite"):
        d.exact_limits(sc, x=x)


def test_exact_limits_of_a_diverged_session_is_an_error():
    p = d.Params()
    p.dt = 5.0  # far past every limit: the run leaves the finite numbers
    r = d.StopRules()
    r.diverge_factor = 1e300  # and is not stopped before it does
    r.max_iterations = 100000
    s = d.Session(d.paper_plane_scene(3), p, r)
    for _ in range(300):  # on past the diverged verdict, to the first non-finite number
        s.step()
        if not np.all(np.isfinite(s.positions)):
            break
    if np.all(np.isfinite(s.positions)):
        pytest.skip("the run stayed finite")
    with pytest.raises(ValueError, match="is not finite"):
        d.exact_limits(s)


# --- memory ---------------------------------------------------------------------------------

def test_a_lower_bounds_view_outlives_a_cut(scenes_dir):
    s = d.Session(d.load_scene(str(scenes_dir / "paper-plane-cut.toml")))
    lb = s.lower_bounds
    before = lb.copy()
    s.step(25)  # the scene's cut at iteration 20 gives the session a new model
    garbage = [np.full(before.size, 7.0) for _ in range(50)]  # reuse freed memory, if any
    assert np.array_equal(lb, before)
    del garbage


def test_a_view_outlives_its_session():
    s = d.Session(d.paper_plane_scene(3))
    s.step()
    views = [s.positions, s.velocities, s.lower_bounds, s.upper_bounds, s.gamma_eff]
    copies = [v.copy() for v in views]
    del s
    for v, c in zip(views, copies):
        assert np.array_equal(v, c)


def test_views_are_read_only():
    s = d.Session(d.paper_plane_scene(3))
    s.step()
    for v in (s.positions, s.lower_bounds, s.gamma_eff):
        with pytest.raises(ValueError):
            v[0] = 1


# --- the GIL --------------------------------------------------------------------------------

def ticks_during(call):
    """How many times a 5 ms Python ticker ran while call() ran, and how long call() took."""
    ticks, stop = [0], threading.Event()

    def ticker():
        while not stop.is_set():
            ticks[0] += 1
            time.sleep(0.005)

    t = threading.Thread(target=ticker)
    t.start()
    time.sleep(0.02)
    ticks[0] = 0
    t0 = time.perf_counter()
    call()
    took = time.perf_counter() - t0
    n = ticks[0]
    stop.set()
    t.join()
    return n, took


def repeat(call, seconds=0.3):
    """call() until `seconds` have passed: one short call tells nothing about the GIL."""
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < seconds:
        call()


def long_session():
    r = d.StopRules()
    r.max_iterations = 3000
    r.rule = "settled"
    return d.Session(d.paper_plane_scene(36), None, r)


@pytest.mark.parametrize("what", ["run", "step", "exact_limits", "monitor_exact_limits"])
def test_long_calls_let_a_python_thread_run(what):
    sc = d.paper_plane_scene(36)
    if what == "run":
        s = long_session()
        call = s.run
    elif what == "step":
        s = long_session()
        call = lambda: s.step(1500)  # noqa: E731
    elif what == "exact_limits":
        call = lambda: repeat(lambda: d.exact_limits(sc))  # noqa: E731
    else:
        a = sc.arrays()
        m = d.Monitor(a["mass"], a["springs"], a["stiffness"], a["rest_length"],
                      a["anchor_stiffness"], a["rest"], a["fixed"])
        call = lambda: repeat(lambda: m.exact_limits(a["rest"], a["gamma"], 0.05))  # noqa: E731
    n, took = ticks_during(call)
    if took < 0.1:
        pytest.skip(f"the call took {took:.3f} s: too short to tell")
    # Holding the GIL the ticker gets at most a tick or two (Python's switch interval is 5 ms);
    # without it, about one tick per 5 ms (fewer on a busy machine).
    assert n >= max(3, took / 0.005 / 10), f"{n} ticks in {took:.2f} s"


def test_a_session_busy_on_another_thread_refuses_other_calls():
    s = long_session()
    t = threading.Thread(target=s.run)
    t.start()
    refused = 0
    while t.is_alive():
        try:
            s.step()
        except RuntimeError as e:
            assert "busy" in str(e)
            refused += 1
            break
        time.sleep(0.001)
    t.join()
    assert refused == 1 or not s.running
