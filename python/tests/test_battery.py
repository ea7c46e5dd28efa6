"""The bad-input battery of the Python module: every entry point that takes a state, an index
array, a flag array, an out array or parameters, fed what a careless user or an attacker would
give it. Each case asserts the exception type (and the name it carries), never a verdict on
bad numbers (docs/embedding.md, "Bad input")."""
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


@pytest.fixture(scope="module")
def mon(arrays):
    a = arrays
    return d.Monitor(a["mass"], a["springs"], a["stiffness"], a["rest_length"],
                     a["anchor_stiffness"], a["rest"], a["fixed"])


def state(arrays, mon):
    x = arrays["rest"].copy()
    x[5, 1] += 0.3
    v = np.zeros((N, 3))
    v[:, 1] = 0.5
    return {"x": x, "v": v, "force": mon.internal_forces(x), "gamma": arrays["gamma"].copy()}


# Every Monitor call that reads a state, with the arrays it reads.
CALLS = {
    "check": (lambda m, s: m.check(s["v"], s["force"], s["gamma"], 0.05), ["v", "force", "gamma"]),
    "check_safe": (lambda m, s: m.check(s["v"], s["force"], s["gamma"], 0.05, policy="safe",
                                        x=s["x"]), ["x", "v", "force", "gamma"]),
    "check_upper": (lambda m, s: m.check(s["v"], s["force"], s["gamma"], 0.05, policy="upper",
                                         factor=0.5), ["v", "force", "gamma"]),
    "upper_bounds": (lambda m, s: m.upper_bounds(s["v"], s["force"], 0.05), ["v", "force"]),
    "safe_bounds": (lambda m, s: m.safe_bounds(s["x"], 0.05), ["x"]),
    "internal_forces": (lambda m, s: m.internal_forces(s["x"]), ["x"]),
    "exact_limits": (lambda m, s: m.exact_limits(s["x"], s["gamma"], 0.05), ["x", "gamma"]),
}

NON_FINITE = [(c, arr, node, bad) for c, (_, reads) in CALLS.items() for arr in reads
              for node in (0, 7, N - 1) for bad in (NAN, INF, -INF)]


@pytest.mark.parametrize("call,array,node,bad", NON_FINITE)
def test_a_non_finite_state_is_an_error_naming_the_node(arrays, mon, call, array, node, bad):
    s = state(arrays, mon)
    CALLS[call][0](mon, s)  # fine as given
    if s[array].ndim == 2:
        s[array][node, node % 3] = bad
    else:
        s[array][node] = bad
    with pytest.raises(ValueError, match=rf"{array}\[{node}\] is not finite"):
        CALLS[call][0](mon, s)


def test_every_node_nan_is_not_ok(arrays, mon):
    s = state(arrays, mon)
    s["v"][:] = NAN
    with pytest.raises(ValueError, match=r"v\[0\]"):
        mon.check(s["v"], s["force"], s["gamma"], 0.05)


BAD_DT = [0.0, -0.05, NAN, INF, -INF]
DT_CALLS = {
    "check": lambda m, s, dt: m.check(s["v"], s["force"], s["gamma"], dt),
    "upper_bounds": lambda m, s, dt: m.upper_bounds(s["v"], s["force"], dt),
    "safe_bounds": lambda m, s, dt: m.safe_bounds(s["x"], dt),
    "exact_limits": lambda m, s, dt: m.exact_limits(s["x"], s["gamma"], dt),
}


@pytest.mark.parametrize("call", sorted(DT_CALLS))
@pytest.mark.parametrize("dt", BAD_DT)
def test_a_bad_dt_is_an_error(arrays, mon, call, dt):
    with pytest.raises(ValueError, match="dt must be"):
        DT_CALLS[call](mon, state(arrays, mon), dt)


@pytest.mark.parametrize("policy", ["fixed", "clamp", "upper", "lower"])
@pytest.mark.parametrize("factor", [-1.0, NAN, INF, -INF])
def test_a_bad_factor_is_an_error(arrays, mon, policy, factor):
    s = state(arrays, mon)
    with pytest.raises(ValueError, match="factor must be"):
        mon.check(s["v"], s["force"], s["gamma"], 0.05, policy=policy, factor=factor)


@pytest.mark.parametrize("call", ["check", "check_safe", "exact_limits"])
@pytest.mark.parametrize("gamma", [-1.0, -1e-300])
def test_negative_damping_is_an_error(arrays, mon, call, gamma):
    s = state(arrays, mon)
    s["gamma"][3] = gamma
    with pytest.raises(ValueError, match=r"gamma\[3\] must be >= 0"):
        CALLS[call][0](mon, s)


def test_upper_with_a_negative_factor_returns_no_negative_damping(arrays, mon):
    s = state(arrays, mon)
    with pytest.raises(ValueError):
        mon.check(s["v"], s["force"], s["gamma"], 0.05, policy="upper", factor=-1)


# --- silent conversions -------------------------------------------------------------------

def make(arrays, **over):
    a = dict(arrays)
    a.update(over)
    return d.Monitor(a["mass"], a["springs"], a["stiffness"], a["rest_length"],
                     a.get("anchor_stiffness"), a.get("rest"), a.get("fixed"))


BAD_SPRINGS_TYPE = ["float64", "float32", "bool", "complex128", "U3", "object"]


@pytest.mark.parametrize("dtype", BAD_SPRINGS_TYPE)
def test_spring_indices_must_be_integers(arrays, dtype):
    with pytest.raises(TypeError, match="springs"):
        make(arrays, springs=arrays["springs"].astype(dtype))


def test_float_indices_are_not_truncated(arrays):
    with pytest.raises(TypeError):
        make(arrays, springs=[[0.0, 1.9], [1.2, 2.7]])


@pytest.mark.parametrize("offset", [N, 2**31, 2**32, 2**32 + 1, 2**62, -1, -(2**32)])
def test_spring_indices_out_of_range_do_not_wrap(arrays, offset):
    sp = arrays["springs"].astype(np.int64)
    sp[2, 1] = offset
    with pytest.raises(ValueError, match="springs: index .* in spring 2"):
        make(arrays, springs=sp)


@pytest.mark.parametrize("dtype", ["int8", "uint8", "int16", "uint16", "int32", "uint32",
                                   "int64", "uint64"])
def test_every_integer_dtype_of_springs_reads_the_same(arrays, mon, dtype):
    m = make(arrays, springs=arrays["springs"].astype(dtype))
    x = arrays["rest"].copy()
    x[5, 1] += 0.3
    assert np.array_equal(m.internal_forces(x), mon.internal_forces(x))


def test_uint64_above_int64_is_out_of_range(arrays):
    sp = arrays["springs"].astype(np.uint64)
    sp[0, 0] = np.uint64(2**63 + 1)
    with pytest.raises(ValueError):
        make(arrays, springs=sp)


@pytest.mark.parametrize("shape", [(3,), (3, 3), (2, 1), (1, 2, 2)])
def test_spring_arrays_of_another_shape_are_refused(arrays, shape):
    with pytest.raises(ValueError, match="springs must have shape"):
        make(arrays, springs=np.zeros(shape, dtype=np.int32))


@pytest.mark.parametrize("fixed", [[256] + [0] * (N - 1), [2] + [0] * (N - 1),
                                   [-1] + [0] * (N - 1)])
def test_fixed_flags_other_than_0_and_1_are_refused(arrays, fixed):
    with pytest.raises(ValueError, match=r"fixed\[0\] must be 0 or 1"):
        make(arrays, fixed=np.array(fixed))


@pytest.mark.parametrize("dtype", ["float64", "complex128", "U1"])
def test_fixed_flags_must_be_bool_or_integers(arrays, dtype):
    with pytest.raises(TypeError, match="fixed"):
        make(arrays, fixed=np.zeros(N, dtype=dtype))


@pytest.mark.parametrize("dtype", ["bool", "uint8", "int64"])
def test_fixed_flags_as_bool_or_0_1_are_read(arrays, dtype):
    f = np.zeros(N, dtype=dtype)
    f[0] = 1
    m = make(arrays, fixed=f)
    assert m.safe_bounds(arrays["rest"], 0.05)[0] == INF


REAL_ARRAYS = ["mass", "stiffness", "rest_length", "anchor_stiffness", "rest"]


@pytest.mark.parametrize("name", REAL_ARRAYS)
@pytest.mark.parametrize("dtype", ["complex128", "U8", "object", "bool"])
def test_topology_arrays_must_be_real(arrays, name, dtype):
    bad = arrays[name].astype(dtype) if dtype != "object" else arrays[name].astype(object)
    with pytest.raises(TypeError, match=name):
        make(arrays, **{name: bad})


@pytest.mark.parametrize("name", ["x", "v", "force", "gamma"])
def test_state_arrays_must_be_real(arrays, mon, name):
    s = state(arrays, mon)
    s[name] = s[name].astype(np.complex128) + 1j
    call = "check_safe"
    with pytest.raises(TypeError, match=name):
        CALLS[call][0](mon, s)


@pytest.mark.parametrize("name", REAL_ARRAYS)
@pytest.mark.parametrize("bad", [NAN, INF, -INF])
def test_non_finite_topology_is_refused(arrays, name, bad):
    a = arrays[name].copy()
    a.flat[0] = bad
    with pytest.raises(ValueError):
        make(arrays, **{name: a})


@pytest.mark.parametrize("dtype", ["float32", "int64", "complex128", "float16"])
def test_an_out_array_of_another_dtype_is_an_error(arrays, mon, dtype):
    s = state(arrays, mon)
    with pytest.raises(TypeError, match="gamma_eff"):
        mon.check(s["v"], s["force"], s["gamma"], 0.05, gamma_eff=np.zeros(N, dtype=dtype))


@pytest.mark.parametrize("out", [np.zeros(N - 1), np.zeros((N, 1)), [0.0] * N])
def test_an_out_array_of_another_shape_or_kind_is_an_error(arrays, mon, out):
    s = state(arrays, mon)
    with pytest.raises((TypeError, ValueError), match="gamma_eff"):
        mon.check(s["v"], s["force"], s["gamma"], 0.05, gamma_eff=out)


def test_a_read_only_out_array_is_an_error(arrays, mon):
    s = state(arrays, mon)
    out = np.zeros(N)
    out.flags.writeable = False
    with pytest.raises(ValueError, match="gamma_eff"):
        mon.check(s["v"], s["force"], s["gamma"], 0.05, gamma_eff=out)


def test_a_float64_out_array_is_written_in_place(arrays, mon):
    s = state(arrays, mon)
    out = np.full(N, -1.0)
    _, ret = mon.check(s["v"], s["force"], s["gamma"], 0.05, policy="clamp", gamma_eff=out)
    assert ret is out or np.shares_memory(ret, out)
    assert np.all(out >= 0)


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
