#pragma once
// The limits of a user's own matrices: a stiffness K assembled by another code (FEM, XPBD,
// a mass-spring engine), lumped masses and nodal damping, judged by the same certified
// analysis `bounds` runs on a scene's model (exact_stability on A = M^-1/2 K M^-1/2, SPEC 7)
// and SPEC 9's per-node safe bound from the Gershgorin rows of the same A (docs/embedding.md,
// "Your own matrices").
#include <Eigen/SparseCore>
#include <vector>

#include "core/analysis/linear_stability_exact.hpp"

namespace dampbound {

/// What linear_limits() judges: K (3N x 3N, symmetric, cm-free units mass unit / s^2), the
/// mass m_i of each node (N) and its damping gamma_i (one value for every node, or N),
/// the step dt (s).
struct MatrixModel {
  const SparseMatrix* K = nullptr;
  std::vector<double> mass;   ///< per node, > 0
  std::vector<double> gamma;  ///< 1 (every node) or N values, >= 0
  double dt = 0;              ///< s, > 0
  /// A damping matrix C (SPEC 10) is not taken yet: where one is given, linear_limits
  /// throws InputError saying so. Nodal damping is the only kind judged.
  const SparseMatrix* C = nullptr;
};

/// The paper's step (semi-implicit Euler) on the matrices, linearised: the same numbers
/// `bounds` prints for a scene whose tangent stiffness is K.
struct MatrixLimits {
  ExactStability exact;  ///< the certified analysis itself (method, spectrum, index, ...)
  /// lambda_max of M^-1 K lies in [lambda_max_lo, lambda_max_hi] (1/s^2).
  double lambda_max_lo = 0, lambda_max_hi = 0;
  /// The largest stable dt at the given gamma (s).
  double dt_max = 0;
  /// gamma_i = g * gamma_i / gamma_ref (gamma_ref = max_i gamma_i; the pattern kept) is
  /// stable at dt for gamma_min <= g < gamma_max; with one gamma for every node that is the
  /// interval of that gamma (mass unit / s).
  double gamma_min = 0, gamma_max = 0;
  double gamma_ref = 0;
  bool stable = false;  ///< the given gamma and dt are stable
  /// SPEC 9 per node: R_i (max over its three rows of sum_s |A_rs|, 1/s^2), gamma_safe_i =
  /// 2 m_i/dt - m_i dt R_i / 2 and dt_safe_i at the node's gamma_i.
  std::vector<double> row_sum, gamma_safe, dt_safe;
};

/// Checks the input (InputError naming the argument: shapes, symmetry to 1e-12 of the largest
/// entry, finite entries, positive masses and dt, non-negative gamma) and runs the analysis.
/// `options` as for exact_stability (a factorisation over its budget throws).
MatrixLimits linear_limits(const MatrixModel& model, const ExactOptions& options = {});

}  // namespace dampbound
