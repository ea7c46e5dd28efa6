#pragma once
// The limits of a user's own matrices: a stiffness K assembled by another code (FEM, XPBD,
// a mass-spring engine), lumped masses, nodal damping and optionally a damping matrix C,
// judged by the same analysis `bounds` runs on a scene's model: exact_stability on
// A = M^-1/2 K M^-1/2 (SPEC 7) and SPEC 9's per-node safe bound from the Gershgorin rows of
// the same A; with C, SPEC 10's index lambda_max(dt^2 A + 2 dt C^) and its generalised safe
// bound, as general_limits() and DampedSafeRows compute them for a scene with dashpots or
// Rayleigh damping (docs/embedding.md, "Your own matrices").
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "core/analysis/damping_limits.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/mass_scaling.hpp"

namespace dampbound {

/// What linear_limits() judges: K (3N x 3N, symmetric, cm-free units mass unit / s^2), the
/// mass m_i of each node (N) and its damping gamma_i (one value for every node, or N),
/// the step dt (s).
struct MatrixModel {
  const SparseMatrix* K = nullptr;
  std::vector<double> mass;   ///< per node, > 0
  std::vector<double> gamma;  ///< 1 (every node) or N values, >= 0
  double dt = 0;              ///< s, > 0
  /// Optional: the damping besides the nodal gamma_i (SPEC 10: dashpots, Rayleigh
  /// alpha M + beta K, anything symmetric positive semi-definite), 3N x 3N, mass unit / s.
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
  /// interval of that gamma (mass unit / s). With C: gamma_min = 0 (C held).
  double gamma_min = 0, gamma_max = 0;
  double gamma_ref = 0;
  bool stable = false;  ///< the given gamma and dt are stable
  /// With C (SPEC 10): `exact` is the analysis of the nodal damping alone (its lambda_max
  /// interval is A's either way); dt_max, gamma_max and stable come from the index
  /// lambda_max(dt^2 A + 2 dt C^) < 4 with C^ = M^-1/2 (Gamma + C) M^-1/2, and damping_min =
  /// lambda_min(C^) (<= 0: some mode is not damped, marginal at best, and `stable` is false).
  bool damping_matrix = false;
  double index = 0;
  double damping_min = 0;
  /// Per node: R_i (max over its three rows of sum_s |A_rs|, 1/s^2) and SPEC 9's
  /// gamma_safe_i = 2 m_i/dt - m_i dt R_i / 2 and dt_safe_i at the node's gamma_i; with C,
  /// SPEC 10's generalised gamma_safe_i and dt_safe_i (Gershgorin on 4 I - 2 dt C^ - dt^2 A).
  std::vector<double> row_sum, gamma_safe, dt_safe;
  /// Empty, or why nothing is guaranteed: K not positive semi-definite (unstable at every
  /// dt: dt_max 0, the gamma interval empty, every gamma_safe_i -inf and dt_safe_i 0), or C
  /// not positive semi-definite (the index does not decide: dt_max, the gamma interval and the
  /// safe bounds NaN, `stable` false).
  std::string reason;
};

/// Checks the input (InputError naming the argument: shapes, symmetry to 1e-12 of the largest
/// entry, finite entries, positive masses and dt, non-negative gamma) and runs the analysis.
/// `options` as for exact_stability (a factorisation over its budget throws).
MatrixLimits linear_limits(const MatrixModel& model, const ExactOptions& options = {});

/// SPEC 11's problem on the matrices (mass_scaling.hpp), checked as linear_limits checks them:
/// K, the masses, C' = C + diag(gamma_i) (C: the damping that does not scale with the masses)
/// and Rayleigh's mass-proportional `alpha` (1/s, >= 0), which does. model.dt is the target.
MassScalingProblem mass_scaling_problem(const MatrixModel& model, double alpha);

}  // namespace dampbound
