"""The bad-input battery of the Python module, arrays: every entry point that takes a state, an
index array, a flag array or an out array, fed what a careless user or an attacker would
give it. Each case asserts the exception type (and the name it carries), never a verdict on
bad numbers (docs/embedding.md, "Bad input")."""
import math

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
