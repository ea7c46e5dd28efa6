#pragma once
// Plain Lanczos (matrix-vector products only, no reorthogonalisation) for the top of a
// symmetric sparse matrix: the recurrence one step at a time, and the estimate that places
// the first shift of certified_largest_eigenvalue (and gives unfactored_largest_eigenvalue
// its tridiagonal T). Nothing certified rests on these numbers alone: a Cholesky
// factorisation or a Rayleigh quotient proves whatever is claimed (linear_stability_cholesky).
#include <functional>
#include <vector>

#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/node_threads.hpp"

namespace dampbound::detail {

/// The start of every Lanczos run here (unit norm): smooth along the rows, its sign flipped at
/// every other node (three rows). A mesh numbered along its rows or layers has neighbours at
/// nearby indices, so the flips put weight on the stiff, oscillating modes where lambda_max
/// lives: 450 steps instead of 750 on the 400 x 400 plane (docs/performance.md); no more on a
/// tetrahedral block, or for -A.
Eigen::VectorXd lanczos_start(Eigen::Index n);

/// Lanczos on S = scale A + diag(d) (`d` null: S = A, and `scale` must be 1), one step at a
/// time, on `threads` node threads (the same bits on any count: detail/symmetric_product.hpp).
/// The operations do not depend on what the caller does with the vectors, so a second run
/// replays the first one's bits: a Ritz vector is formed that way, without storing the basis.
///
/// Scalar float: the recurrence of A's values rounded to float (`scale` 1 and `d` null only),
/// with float vectors and alpha, beta summed in double: about half the bytes per step, for the
/// estimate that only places a shift (docs/performance.md, "The estimate in single
/// precision"). Its top Ritz value is one of A + E, |E| <= 2^-24 |A| + 2^-150 entry by entry
/// (the second term below float's normal range), so within matrix_error() = 2^-24 max_r
/// sum_s |A_rs| + 2^-150 (entries per row) of one of A's (Weyl), up to the float recurrence's
/// own rounding, of the same order; infinite where an entry lies beyond float's range.
template <class Scalar>
class LanczosRecurrence {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  LanczosRecurrence(const SparseMatrix& A, int threads, double scale = 1,
                    const Eigen::VectorXd* d = nullptr);
  /// v_j: the vector before step j.
  const Vector& vector() const { return v_; }
  /// Step j: alpha_j and beta_j appended, v_{j+1} formed; false when beta_j = 0 (an
  /// invariant subspace: the Ritz values are eigenvalues).
  bool step();
  /// The threads of the next steps (the same bits on any count).
  void set_threads(int threads) { pool_.set_threads(threads); }
  /// How far the matrix of the recurrence may lie from S in the 2-norm: 0 in double.
  double matrix_error() const { return matrix_error_; }
  std::vector<double> alpha, beta;  ///< T's diagonal and off-diagonal so far

 private:
  const SparseMatrix& A_;
  const Eigen::VectorXd* d_;
  double scale_;
  NodeThreads pool_;
  std::vector<float> single_;  ///< float: A's values rounded
  double matrix_error_ = 0;
  Vector v_, previous_, w_;
  double b_ = 0;
  std::vector<double> partial_;  ///< the blocks' partial sums of alpha and beta^2
};

/// A rough top Ritz value of S and an estimate of how far below lambda_max it still is.
struct TopEstimate {
  double theta = 0;     ///< the top Ritz value (below lambda_max, up to rounding)
  double residual = 0;  ///< its Lanczos residual: some eigenvalue lies within it
  double error = 0;     ///< lambda_max - theta extrapolated from the last checkpoints
  int steps = 0;
  /// How far the recurrence's matrix may lie from S (LanczosRecurrence::matrix_error): theta
  /// is a Ritz value of that matrix, and `residual` and `error` are measured against it.
  double matrix_error = 0;
  std::vector<double> alpha, beta;  ///< T
  /// T's unit eigenvector of theta, the Ritz vector's coefficients in the Lanczos basis
  /// (empty when inverse iteration failed).
  std::vector<double> y;
};

/// Up to `max_steps` steps (at most n), checked every `check`: the Ritz value converges
/// geometrically, so with d the rise over the last window and q its ratio to the rise over
/// the one before (kept in [0.5, 0.9]: a sudden drop in the rise is more often a pause than
/// convergence), lambda_max - theta ~ d q / (1 - q). It stops once that is below `tolerance`
/// |theta|: for the first shift 1e-7 in windows of 50 steps (a shift that close separates
/// even a clustered top). `after_step`, when given, is called after every step; false stops
/// the estimate there.
inline constexpr int kLanczosSteps = 1000, kLanczosCheck = 50;
/// How long the product's threads poll for the next product before they sleep.
inline constexpr int kLanczosSpinMicroseconds = 200;
template <class Scalar>
TopEstimate lanczos_estimate(LanczosRecurrence<Scalar>& lanczos, Eigen::Index n,
                             int max_steps = kLanczosSteps, int check = kLanczosCheck,
                             double tolerance = 1e-7, const std::function<bool()>& after_step = {});

}  // namespace dampbound::detail
