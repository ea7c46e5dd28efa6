#pragma once
// A user's own matrices and vectors from Python (python/linear_limits.cpp): what
// linear_limits and mass_scaling take.
#include <vector>

#include "dampbound/physics/stiffness.hpp"
#include "python/arrays.hpp"

namespace dampbound::python {

/// A scipy.sparse matrix (or anything scipy.sparse.coo_matrix takes) as an Eigen matrix;
/// TypeError naming `name` otherwise.
SparseMatrix sparse_of(const py::object& M, const char* name);
/// A number or a 1-D array as doubles; ValueError naming `name` otherwise.
std::vector<double> vector_of(const py::object& v, const char* name);

}  // namespace dampbound::python
