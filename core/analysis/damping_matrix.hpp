#pragma once
// SPEC 10's damping matrix besides the nodal Gamma, linearised at a state:
//   C' = alpha M + beta K(x) + sum over springs kd_ij [P, -P; -P, P] + diag(kd_a,i I),
// P = d d^T the spring's direction pattern placed as in K. The step never assembles it
// (forces.hpp's damping_forces() applies it spring by spring); the exact analysis and
// implicit Euler do.
#include <vector>

#include "core/analysis/linear_stability.hpp"
#include "core/model.hpp"

namespace dampbound {

/// C' over the free nodes (3 n_free square, symmetric, free_blocks() order) at positions x.
/// `clamp_compression` clamps K's (1 - l0/l) at 0 as tangent_stiffness() does. A spring of no
/// direction adds nothing (SPEC 1).
SparseMatrix spring_damping_matrix(const Model& model, const std::vector<Vec3>& x,
                                   bool clamp_compression = false);

/// M^-1/2 (diag(gamma_i I) + C') M^-1/2 over the free nodes: SPEC 10's C^, with the nodal
/// gamma_i given per node (fixed nodes ignored).
SparseMatrix weighted_damping(const Model& model, const std::vector<Vec3>& x,
                              const std::vector<double>& gamma);

}  // namespace dampbound
