"""The module refuses what the CLI refuses, naming the argument: geometry scales, densities and
moduli that are not finite or not positive; indices outside int32 or not integers; matrices
that are not real numbers; cells given as a plain list of index rows."""
import numpy as np
import pytest
import scipy.sparse as sp

import dampbound

POINTS = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
TRI = {"triangle": np.array([[0, 1, 2], [0, 2, 3]])}


@pytest.mark.parametrize("value", [float("nan"), 0.0, -1.0, float("inf")])
def test_scale_not_finite_or_not_positive(value):
    with pytest.raises(ValueError, match=r"^scale must"):
        dampbound.Scene.from_arrays(POINTS, TRI, scale=value)


@pytest.mark.parametrize("name", ["density", "young"])
@pytest.mark.parametrize("value", [-1.0, float("nan"), float("inf")])
def test_density_and_modulus_not_negative_or_not_finite(name, value):
    with pytest.raises(ValueError, match=rf"^{name} must"):
        dampbound.Scene.from_arrays(POINTS, TRI, **{name: value})


def test_a_valid_scene_still_builds():
    s = dampbound.Scene.from_arrays(POINTS, TRI, scale=2.0, density=0.0, young=0.0)
    assert len(s.arrays()["mass"]) == 4


def test_an_index_outside_int32_does_not_wrap():
    cells = {"triangle": np.array([[0, 1, 2**32 + 3]], dtype=np.int64)}
    with pytest.raises(ValueError, match=r"triangle cells: 4294967299 .* outside the int32 range"):
        dampbound.Scene.from_arrays(POINTS, cells)


def test_float_indices_are_not_truncated():
    cells = {"triangle": np.array([[0, 1, 2.7]])}
    with pytest.raises(ValueError, match=r"triangle cells: 2.7 at entry 2 is not a whole number"):
        dampbound.Scene.from_arrays(POINTS, cells)
    with pytest.raises(ValueError, match=r"perturb: 1.5 .* is not a whole number"):
        dampbound.Scene.from_arrays(POINTS, TRI, perturb=1.5)
    with pytest.raises(TypeError, match=r"triangle cells: expected an array of integers"):
        dampbound.Scene.from_arrays(POINTS, {"triangle": np.array([[True, False, True]])})
    # whole numbers held as floats (meshio's tags in some formats) are taken as they are
    dampbound.Scene.from_arrays(POINTS, {"triangle": np.array([[0.0, 1.0, 2.0]])})


def test_a_plain_list_of_cells_is_refused_naming_the_argument():
    with pytest.raises(TypeError, match=r"^cells: give a dict"):
        dampbound.Scene.from_arrays(POINTS, [[0, 1, 2], [0, 2, 3]])
    with pytest.raises(TypeError, match=r"^cells: give a dict"):
        dampbound.Scene.from_arrays(POINTS, np.array([[0, 1, 2]]))
    # the two accepted forms
    dampbound.Scene.from_arrays(POINTS, [("triangle", [[0, 1, 2]])])
    dampbound.Scene.from_arrays(POINTS, {"triangle": [[0, 1, 2]]})


def two_node_K():
    k = 1.0
    K = np.zeros((6, 6))
    for a, b, s in ((0, 0, 1), (3, 3, 1), (0, 3, -1), (3, 0, -1)):
        K[a, b] = s * k
    return K


@pytest.mark.parametrize("dtype", [np.complex128, np.bool_])
def test_a_matrix_of_non_real_numbers_is_refused(dtype):
    K = sp.coo_matrix(two_node_K().astype(dtype))
    with pytest.raises(TypeError, match=r"^K"):
        dampbound.linear_limits(K, [1.0, 1.0], dt=0.1)


def test_a_text_matrix_is_refused():
    K = np.array([["1", "0"], ["0", "1"]])
    with pytest.raises(TypeError, match=r"^K"):
        dampbound.linear_limits(K, [1.0, 1.0], dt=0.1)


def test_a_text_or_complex_mass_is_refused():
    K = sp.coo_matrix(two_node_K())
    with pytest.raises(TypeError, match=r"^mass"):
        dampbound.linear_limits(K, np.array([1 + 1j, 1]), dt=0.1)
    with pytest.raises(TypeError, match=r"^mass"):
        dampbound.linear_limits(K, np.array(["1", "1"]), dt=0.1)


def test_results_say_their_answer_in_repr(scenes_dir):
    scene = dampbound.load_scene(str(scenes_dir / "two-node.toml"))
    e = dampbound.exact_limits(scene)
    text = repr(e)
    assert text.startswith("ExactStability(stable (exact linear analysis at the state)")
    assert f"dt < {e.dt_max:.6g} s at this gamma" in text
    s = dampbound.Session(scene)
    r = s.run()
    assert repr(r).startswith(f"RunResult({r.outcome.replace('_', ' ')}")
