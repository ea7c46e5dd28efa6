#pragma once
// NumPy arrays in and out of the module without copies where the layout allows: a float64
// (N, 3) array whose rows are evenly spaced and whose columns are adjacent is read in place
// (any C-ordered array, or a slice of rows); anything else is converted once.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "core/model.hpp"
#include "core/monitor.hpp"

namespace dampbound::python {

namespace py = pybind11;

/// A float64 array as given when its layout allows, else a C-ordered float64 copy.
inline py::array_t<double> as_float64(const py::handle& h) {
  auto a = py::array_t<double>::ensure(h);
  if (!a) throw py::type_error("expected an array of numbers");
  return a;
}

/// (N, 3) positions/velocities/forces read in place (rows strided, columns adjacent).
/// `keep` holds the array (or its copy) alive while the view is used.
inline NodeVectors node_vectors_of(const py::handle& h, const char* name,
                                   py::array_t<double>& keep) {
  keep = as_float64(h);
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
  keep = as_float64(h);
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

void bind_monitor(py::module_& m);
void bind_analysis(py::module_& m);

}  // namespace dampbound::python
