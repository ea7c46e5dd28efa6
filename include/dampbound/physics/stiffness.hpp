#pragma once
// The paper's mass-spring system linearised at a state: the tangent stiffness K = -dF/dx
// (SPEC 7), its mass weighting M^-1/2 K M^-1/2, and SPEC 10's damping matrix C' besides the
// nodal Gamma. Physics, not analysis: implicit Euler solves with them and the safe bound
// reads them; the exact analyses (core/analysis/) take their eigenvalues.
//   C' = alpha M + beta K(x) + sum over springs kd_ij [P, -P; -P, P] + diag(kd_a,i I),
// P = d d^T the spring's direction pattern placed as in K. The step never assembles C'
// (forces.hpp's damping_forces() applies it spring by spring).
#include "dampbound/physics/export.hpp"
#include <Eigen/SparseCore>
#include <vector>

#include "dampbound/physics/model.hpp"

namespace dampbound DAMPBOUND_API {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// The 3-block of each node among the free nodes (block b = rows 3b..3b+2), -1 for a fixed
/// node. Fixed nodes never move, so they have no degree of freedom in any linear analysis.
std::vector<int> free_blocks(const Model& model, int* free_count = nullptr);

/// Tangent stiffness K = -dF/dx over the free nodes (3 n_free square, symmetric), at
/// positions x. Per spring (i, j), l = |x_j - x_i|, d = (x_j - x_i)/l:
///   B = kappa_ij [ (1 - l0/l) I + (l0/l) d d^T ],  K_ii += B, K_jj += B, K_ij = K_ji -= B;
/// per anchor K_ii += kappa_a,i I. At rest (l = l0) B = kappa d d^T. A spring of zero length
/// is skipped, as in internal_forces (SPEC 1). `clamp_compression` replaces (1 - l0/l) by
/// max(0, 1 - l0/l) so that K stays positive semi-definite (what implicit Euler solves with;
/// exact at rest and under tension). `threads` (0: one per CPU) assemble it in node ranges,
/// the same bits on any count.
SparseMatrix tangent_stiffness(const Model& model, const std::vector<Vec3>& x,
                               bool clamp_compression = false, int threads = 1);

/// M^-1/2 K M^-1/2 over the free nodes: symmetric, with the eigenvalues of M^-1 K. The
/// second form scales K in place (no copy of a big matrix). `threads` as above.
SparseMatrix mass_weighted(const Model& model, const SparseMatrix& K, int threads = 1);
SparseMatrix mass_weighted(const Model& model, SparseMatrix&& K, int threads = 1);

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
