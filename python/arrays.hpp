#pragma once
// NumPy arrays in and out of the module without copies where the layout allows: a float64
// (N, 3) array whose rows are evenly spaced and whose columns are adjacent is read in place
// (any C-ordered array, or a slice of rows); anything else is converted once.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/physics/damping_ratio.hpp"
#include "dampbound/monitor.hpp"
#include "dampbound/physics/model.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound::python {

namespace py = pybind11;

/// A float64 array as given when its layout allows, else a C-ordered float64 copy. Only real
/// numbers convert: a complex, boolean, string or object array is a TypeError naming `name`
/// (no imaginary part is dropped, no text parsed).
inline py::array_t<double> as_float64(const py::handle& h, const char* name) {
  py::array a = py::array::ensure(h);
  if (!a) throw py::type_error(std::string(name) + " must be an array of real numbers");
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::type_error(std::string(name) + " must be an array of real numbers, got dtype " +
                         std::string(py::str(a.dtype())));
  auto d = py::array_t<double>::ensure(a);
  if (!d) throw py::type_error(std::string(name) + " must be an array of real numbers");
  return d;
}

/// A writeable float64 (N,) output array, used in place: another dtype is a TypeError (a
/// converted copy would take the results where the caller never sees them), another shape or
/// a read-only array a ValueError.
inline py::array_t<double> out_array(const py::object& h, const char* name, py::ssize_t n) {
  if (h.is_none()) return py::array_t<double>(n);
  if (!py::isinstance<py::array>(h) || !py::isinstance<py::array_t<double>>(h))
    throw py::type_error(std::string(name) + " must be a float64 NumPy array");
  auto a = py::reinterpret_borrow<py::array_t<double>>(h);
  if (a.ndim() != 1 || a.shape(0) != n || !a.writeable() ||
      a.strides(0) % static_cast<py::ssize_t>(sizeof(double)) != 0 || a.strides(0) <= 0)
    throw py::value_error(std::string(name) + " must be a writeable float64 array of shape (" +
                          std::to_string(n) + ",)");
  return a;
}

/// Node or spring indices: an integer array (a float, bool or complex one is a TypeError: no
/// truncation), every value in [0, n) (a ValueError naming the first that is not: no wrap to
/// int), as a C-ordered int32 array of shape `cols` wide (2 for springs) or (N,) when cols is 0.
inline py::array_t<int, py::array::c_style> index_array(const py::handle& h, const char* name,
                                                        long long n, int cols) {
  py::array a = py::array::ensure(h);
  if (!a) throw py::type_error(std::string(name) + " must be an integer array");
  const char kind = a.dtype().kind();
  // An empty list has dtype float64: no value to truncate, read as no index.
  const bool empty_list = a.size() == 0 && !py::isinstance<py::array>(h);
  if (kind != 'i' && kind != 'u' && !empty_list)
    throw py::type_error(std::string(name) + " must be an integer array, got dtype " +
                         std::string(py::str(a.dtype())));
  if (cols > 0 && a.size() == 0 && a.ndim() == 1) a = a.attr("reshape")(0, cols);
  if (cols > 0 ? (a.ndim() != 2 || a.shape(1) != cols) : a.ndim() != 1)
    throw py::value_error(std::string(name) + " must have shape " +
                          (cols > 0 ? "(S, " + std::to_string(cols) + ")" : std::string("(N,)")));
  // Read as Python integers' own width, so no value wraps before it is compared.
  const bool unsigned_ = kind == 'u';
  auto wide = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(
      unsigned_ ? a.attr("astype")("uint64") : a.attr("astype")("int64"));
  py::array_t<int, py::array::c_style> out(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
  const long long* in = wide.data();
  int* w = out.mutable_data();
  for (py::ssize_t k = 0; k < a.size(); ++k) {
    const long long v = in[k];
    // uint64 above 2^63 reads as negative: out of range either way.
    if (v < 0 || v >= n || (unsigned_ && static_cast<unsigned long long>(v) >= static_cast<unsigned long long>(n)))
      throw py::value_error(std::string(name) + ": index " +
                            (unsigned_ ? std::to_string(static_cast<unsigned long long>(v))
                                       : std::to_string(v)) +
                            (cols > 0 ? " in spring " + std::to_string(k / cols)
                                      : " at entry " + std::to_string(k)) +
                            " is not in 0.." +
                            std::to_string(n - 1));
    w[k] = static_cast<int>(v);
  }
  return out;
}

/// Per-node flags: bool, or integers 0 and 1 (256 or 0.5 is an error, not a silent 0).
inline std::vector<std::uint8_t> flags_of(const py::handle& h, const char* name) {
  py::array a = py::array::ensure(h);
  if (!a) throw py::type_error(std::string(name) + " must be a bool or 0/1 integer array");
  const char kind = a.dtype().kind();
  if (kind != 'b' && kind != 'i' && kind != 'u')
    throw py::type_error(std::string(name) + " must be a bool or 0/1 integer array, got dtype " +
                         std::string(py::str(a.dtype())));
  if (a.ndim() != 1) throw py::value_error(std::string(name) + " must have shape (N,)");
  auto wide = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(
      kind == 'u' ? a.attr("astype")("uint64") : a.attr("astype")("int64"));
  std::vector<std::uint8_t> out(static_cast<size_t>(a.size()));
  for (py::ssize_t k = 0; k < a.size(); ++k) {
    const long long v = wide.data()[k];
    if (v != 0 && v != 1)
      throw py::value_error(std::string(name) + "[" + std::to_string(k) + "] must be 0 or 1 (or bool)");
    out[static_cast<size_t>(k)] = static_cast<std::uint8_t>(v);
  }
  return out;
}

/// What every call that takes Params checks first: core's validate(), the CLI's words.
inline void require_valid(const Params& p) {
  if (const auto why = validate(p)) throw py::value_error(*why);
}

/// The scene and parameters a call uses: `params` (default the scene's) validated, and a
/// damping ratio given as Params.zeta resolved as the CLI resolves --zeta (gamma_i = zeta * 2
/// sqrt(m_i kappa_i) at each node, core/physics/damping_ratio.hpp) on a copy of the scene, which is
/// made only then.
class ResolvedScene {
 public:
  ResolvedScene(const SceneSpec& scene, const Params* params)
      : params_(params ? *params : scene.params), scene_(&scene) {
    require_valid(params_);
    if (params_.zeta) {
      copy_ = scene;
      resolve_zeta(copy_->model, params_);
      scene_ = &*copy_;
    }
    // What the CLI refuses (app/options.hpp require_magnitudes): numbers whose intermediates
    // overflow get no verdict.
    if (const auto why = magnitude_problem(compile_model(scene_->model, params_), params_.dt))
      throw py::value_error(*why);
  }
  const SceneSpec& scene() const { return *scene_; }
  const Params& params() const { return params_; }

 private:
  Params params_;
  const SceneSpec* scene_;
  std::optional<SceneSpec> copy_;
};

/// (N, 3) positions/velocities/forces read in place (rows strided, columns adjacent).
/// `keep` holds the array (or its copy) alive while the view is used.
inline NodeVectors node_vectors_of(const py::handle& h, const char* name,
                                   py::array_t<double>& keep) {
  keep = as_float64(h, name);
  if (keep.ndim() != 2 || keep.shape(1) != 3)
    throw py::value_error(std::string(name) + " must have shape (N, 3)");
  const auto s0 = keep.strides(0), s1 = keep.strides(1);
  if (s1 != sizeof(double) || s0 % static_cast<py::ssize_t>(sizeof(double)) != 0 || s0 <= 0)
    keep = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(keep);
  return node_vectors(keep.data(), keep.shape(0), keep.strides(0) / sizeof(double));
}

/// (N,) values read in place (any positive stride that is a whole number of doubles).
inline NodeScalars node_scalars_of(const py::handle& h, const char* name,
                                   py::array_t<double>& keep) {
  keep = as_float64(h, name);
  if (keep.ndim() != 1) throw py::value_error(std::string(name) + " must have shape (N,)");
  const auto s0 = keep.strides(0);
  if (s0 % static_cast<py::ssize_t>(sizeof(double)) != 0 || s0 <= 0)
    keep = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(keep);
  return node_scalars(keep.data(), keep.shape(0), keep.strides(0) / sizeof(double));
}

/// A read-only (N, 3) view of core's positions or velocities, kept alive by `owner`.
inline py::array_t<double> view_of(const std::vector<Vec3>& v, const py::handle& owner) {
  py::array_t<double> a(
      {static_cast<py::ssize_t>(v.size()), py::ssize_t{3}},
      {static_cast<py::ssize_t>(sizeof(Vec3)), static_cast<py::ssize_t>(sizeof(double))},
      v.empty() ? nullptr : v.front().data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

/// A read-only (N,) view of a per-node vector of core, kept alive by `owner`.
template <typename T>
py::array_t<T> view_of(const std::vector<T>& v, const py::handle& owner) {
  py::array_t<T> a({static_cast<py::ssize_t>(v.size())}, {static_cast<py::ssize_t>(sizeof(T))},
                   v.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

/// A read-only (N,) view of a vector inside an object `data` that a shared_ptr owns: the view
/// keeps `data` itself alive (a capsule), not the Python object that held it when the view was
/// taken, so the view stays valid when that object moves on to new data (a Session after a cut).
template <typename T, typename Owner>
py::array_t<T> view_of_shared(const std::vector<T>& v, std::shared_ptr<const Owner> data) {
  auto* held = new std::shared_ptr<const Owner>(std::move(data));
  py::capsule owner(held, [](void* p) { delete static_cast<std::shared_ptr<const Owner>*>(p); });
  return view_of(v, owner);
}

/// A Session in use by a call that let go of the GIL (run, step, exact_limits): every other
/// call on it raises RuntimeError instead of racing it. The set is read and written only with
/// the GIL held.
class SessionInUse {
 public:
  explicit SessionInUse(const void* session);
  ~SessionInUse();
  SessionInUse(const SessionInUse&) = delete;
  SessionInUse& operator=(const SessionInUse&) = delete;
  /// Raises RuntimeError when a call on `session` runs without the GIL.
  static void require_idle(const void* session);

 private:
  const void* session_;
};

/// `d` as an instance of the module's dict subclass `kind` (Answer, Suggestion: bind_answers):
/// the same keys, with a repr that is the answer line(s) in d["answer"], the CLI's first lines.
inline py::object answer_dict(const char* kind, const py::dict& d) {
  return py::module_::import("dampbound").attr(kind)(d);
}
void bind_answers(py::module_& m);
void bind_monitor(py::module_& m);
void bind_analysis(py::module_& m);

}  // namespace dampbound::python
