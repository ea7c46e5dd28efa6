// dampbound.linear_limits(K, mass, dt=, gamma=, C=None): a user's own scipy.sparse stiffness
// judged by the analysis `bounds` runs (core/analysis/linear_limits.hpp). The matrix comes in
// as its COO triplets (any scipy.sparse format, or a dense array, converted in Python).
#include "core/analysis/linear_limits.hpp"

#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "dampbound/physics/error.hpp"
#include "python/arrays.hpp"
#include "python/matrices.hpp"

namespace dampbound::python {

/// A scipy.sparse matrix (or anything scipy.sparse.coo_matrix takes) as an Eigen matrix.
SparseMatrix sparse_of(const py::object& M, const char* name) {
  py::module_ sp = py::module_::import("scipy.sparse");
  py::object coo;
  try {
    coo = sp.attr("coo_matrix")(M);
  } catch (const py::error_already_set&) {
    throw py::type_error(std::string(name) + ": expected a scipy.sparse matrix or a 2-D array");
  }
  const auto shape = coo.attr("shape").cast<std::pair<py::ssize_t, py::ssize_t>>();
  const auto rows = py::array_t<long long, py::array::forcecast>::ensure(coo.attr("row"));
  const auto cols = py::array_t<long long, py::array::forcecast>::ensure(coo.attr("col"));
  // Real numbers only: a complex, bool or text matrix is a TypeError naming it (as_float64).
  const auto vals = as_float64(coo.attr("data"), name);
  if (!rows || !cols || !vals)
    throw py::type_error(std::string(name) + ": entries must be numbers");
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(size_t(vals.size()));
  for (py::ssize_t k = 0; k < vals.size(); ++k)
    t.emplace_back(Eigen::Index(rows.at(k)), Eigen::Index(cols.at(k)), vals.at(k));
  SparseMatrix out(Eigen::Index(shape.first), Eigen::Index(shape.second));
  out.setFromTriplets(t.begin(), t.end());  // duplicates summed, as scipy does
  return out;
}

std::vector<double> vector_of(const py::object& v, const char* name) {
  const auto a = as_float64(v, name);
  if (a.ndim() > 1)
    throw py::value_error(std::string(name) + ": expected a number or a 1-D array");
  std::vector<double> out(size_t(a.size()));
  for (py::ssize_t k = 0; k < a.size(); ++k) out[size_t(k)] = a.data()[k];
  return out;
}

namespace {

py::array_t<double> array_of(const std::vector<double>& v) {
  return py::array_t<double>(py::ssize_t(v.size()), v.data());
}

}  // namespace

void bind_linear_limits(py::module_& m) {
  py::class_<MatrixLimits>(m, "MatrixLimits",
                           "linear_limits' result: the paper's step on the matrices, linearised.")
      .def_readonly("exact", &MatrixLimits::exact, "the certified analysis (ExactStability)")
      .def_property_readonly(
          "lambda_max",
          [](const MatrixLimits& r) { return py::make_tuple(r.lambda_max_lo, r.lambda_max_hi); },
          "(lo, hi): lambda_max of M^-1 K lies in it (1/s^2; hi certified by Cholesky)")
      .def_readonly("dt_max", &MatrixLimits::dt_max, "largest stable dt at the given gamma (s)")
      .def_readonly("gamma_min", &MatrixLimits::gamma_min, "stable for gamma_min <= g < gamma_max")
      .def_readonly("gamma_max", &MatrixLimits::gamma_max,
                    "the largest stable g at dt, gamma_i = g * gamma_i / gamma_ref (one gamma "
                    "for every node: that gamma)")
      .def_readonly("gamma_ref", &MatrixLimits::gamma_ref, "max_i gamma_i as given")
      .def_readonly("stable", &MatrixLimits::stable, "the given gamma and dt are stable")
      .def_readonly("damping_matrix", &MatrixLimits::damping_matrix, "a C was given (SPEC 10)")
      .def_readonly("index", &MatrixLimits::index,
                    "with C: lambda_max(dt^2 A + 2 dt C^), stable below 4")
      .def_readonly("damping_min", &MatrixLimits::damping_min,
                    "with C: lambda_min(C^) (1/s); <= 0 leaves a mode undamped")
      .def_property_readonly(
          "row_sum", [](const MatrixLimits& r) { return array_of(r.row_sum); },
          "SPEC 9's R_i per node (1/s^2)")
      .def_property_readonly(
          "gamma_safe", [](const MatrixLimits& r) { return array_of(r.gamma_safe); },
          "SPEC 9's gamma_safe_i per node")
      .def_property_readonly(
          "dt_safe", [](const MatrixLimits& r) { return array_of(r.dt_safe); },
          "SPEC 9's dt_safe_i per node at its gamma_i (s)")
      .def_readonly("reason", &MatrixLimits::reason,
                    "empty, or why nothing is guaranteed (K or C not positive semi-definite)")
      .def("__repr__", [](const MatrixLimits& r) {
        return "<MatrixLimits lambda_max in [" + std::to_string(r.lambda_max_lo) + ", " +
               std::to_string(r.lambda_max_hi) + "], dt_max " + std::to_string(r.dt_max) +
               ", gamma_max " + std::to_string(r.gamma_max) + ">";
      });
  m.def(
      "linear_limits",
      [](const py::object& K, const py::object& mass, double dt, const py::object& gamma,
         const py::object& C) {
        const SparseMatrix k = sparse_of(K, "K");
        MatrixModel mm;
        mm.K = &k;
        mm.mass = vector_of(mass, "mass");
        mm.gamma = vector_of(gamma, "gamma");
        mm.dt = dt;
        SparseMatrix c;
        if (!C.is_none()) {
          c = sparse_of(C, "C");
          mm.C = &c;
        }
        py::gil_scoped_release unlocked;
        return linear_limits(mm);
      },
      py::arg("K"), py::arg("mass"), py::kw_only(), py::arg("dt"), py::arg("gamma") = 0.0,
      py::arg("C") = py::none(),
      "The limits of your own matrices (docs/embedding.md, 'Your own matrices'): K a symmetric "
      "scipy.sparse stiffness (3N x 3N, rows 3i..3i+2 node i), mass (N,), gamma one value or "
      "(N,), dt in s, C an optional symmetric damping matrix (3N x 3N, SPEC 10: dashpots, "
      "Rayleigh damping). The same analysis as `bounds`: lambda_max interval, dt_max, "
      "gamma_max, per-node gamma_safe and dt_safe (with C: SPEC 10's index and generalised "
      "safe bound). ValueError names a bad argument.");
}

}  // namespace dampbound::python
