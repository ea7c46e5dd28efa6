#pragma once
// Extreme eigenvalues of a large symmetric sparse matrix in a certified interval, by sparse
// Cholesky (SPEC 7, 9; CHOLMOD's supernodal factorisation): Gershgorin's bound caps the
// shifts, shift-and-invert Lanczos just above lambda_max (one factorisation, a few solves),
// then a factorisation of (sigma I - A) as the certificate that no eigenvalue lies above hi.
// A factorisation succeeds exactly when the matrix is positive definite, so a success proves
// lambda_max < sigma up to its rounding, which a bound computed from the factor covers
// (hi = sigma + that bound); the Rayleigh quotient of the Ritz vector proves lambda_max >= lo. docs/performance.md has
// the algorithm and its costs.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>

#include "dampbound/analysis/linear_stability.hpp"

namespace dampbound {

/// Gershgorin's discs of a symmetric matrix (SPEC 9): every eigenvalue lies in [lo, hi],
/// lo = min_r (A_rr - sum_{s != r} |A_rs|), hi = max_r (A_rr + sum_{s != r} |A_rs|). For
/// A = M^-1/2 K M^-1/2 with A_rr >= 0, hi is the largest R_i of SPEC 9 (units of A).
struct GershgorinBounds {
  double lo = 0;
  double hi = 0;
};
GershgorinBounds gershgorin_bounds(const SparseMatrix& A);

/// No limit on what one factorisation may cost (the default of every function below).
inline constexpr double kNoFactorBudget = std::numeric_limits<double>::infinity();

/// Thrown before any numeric factorisation when CHOLMOD's analysis of the matrix's pattern
/// predicts that one factorisation would take more floating-point operations than the
/// caller's budget (`max_factor_flops`): a 3-D mesh's factor fills in (the 46^3-node
/// tetrahedral block: 0.9 TFlop and 2.2 GB per factorisation; docs/performance.md).
class FactorisationOverBudget : public std::runtime_error {
 public:
  /// `amd_only`: the prediction is AMD's ordering's (of the nodes when the rows come in
  /// threes), from the quick check of a matrix of more than 500 000 rows, and over kAmdSlack
  /// (32) times the budget.
  FactorisationOverBudget(double flops, double bytes, double budget, bool amd_only = false);
  double flops;   ///< CHOLMOD's prediction for one factorisation
  double bytes;   ///< the factor's size (8 bytes per entry of L)
  double budget;  ///< the caller's limit (flops)
  bool amd_only;
};

/// A certified enclosure lo <= lambda <= hi of one extreme eigenvalue (units of the matrix),
/// and what it cost.
struct EigenInterval {
  double lo = 0;
  double hi = 0;
  int factorizations = 0;  ///< numeric sparse Cholesky factorisations (one symbolic analysis)
  int solves = 0;          ///< solves with a factor (two triangular solves each)
  int lanczos_steps = 0;   ///< matrix-vector Lanczos steps that placed the first shift
  /// false only when even Gershgorin's shift did not factor (rounding): then [lo, hi] is
  /// [largest diagonal entry, Gershgorin's bound], still an enclosure, but wide.
  bool certified = true;
};

/// Largest eigenvalue of symmetric A. hi is certified by a successful Cholesky factorisation
/// of sigma I - A: hi = sigma + delta, delta a bound on that factorisation's rounding computed
/// from its factor (detail/cholesky_rounding.hpp; 1e-12 to 1e-11 of |lambda| on the meshes
/// measured), or Gershgorin's bound when that is lower; lo is the Rayleigh quotient of the
/// Ritz vector less a bound on its rounding (a lower bound for any vector). hi - lo <= ~1e-10 |lambda| + 1e-11 (Gershgorin width). Up to 400 rows
/// the dense eigenvalue is returned (lo = hi). `vector`: the unit Ritz vector. `threads`:
/// the Lanczos estimate's matrix-vector products run on this many threads (0: one per CPU;
/// matrices under 32768 rows stay on one), with the same bits on any count.
/// On two or more threads one of them prepares the factorisations (the pattern analysis) while
/// the others start the estimate, with the same bits. `max_factor_flops`: throws
/// FactorisationOverBudget when one factorisation would cost more, as soon as the pattern
/// analysis says so (the estimate stops there) and before any factorisation.
EigenInterval certified_largest_eigenvalue(const SparseMatrix& A,
                                           Eigen::VectorXd* vector = nullptr, int threads = 1,
                                           double max_factor_flops = kNoFactorBudget);
namespace detail {
class ShiftedCholesky;
}
/// The same with its factorisations in `factors`: made for A when empty, else given A's values,
/// which keeps their pattern analysis where A has the pattern analysed before (the limit
/// searches' of detail/definite_root.hpp, whose index matrices have the pattern of the
/// index at the scene's gamma and dt).
EigenInterval certified_largest_eigenvalue(const SparseMatrix& A,
                                           std::unique_ptr<detail::ShiftedCholesky>& factors,
                                           int threads = 1,
                                           double max_factor_flops = kNoFactorBudget,
                                           Eigen::VectorXd* vector = nullptr);

/// Without a factorisation (for a matrix over the budget): lambda_max(A) in [lo, hi], with
/// hi Gershgorin's bound and lo the Rayleigh quotient on A of a Ritz vector, less its
/// rounding. The vector is plain Lanczos's top Ritz vector of S = scale A + diag(d) (`d`
/// null: S = A) after at most `max_steps` steps (fewer once its Ritz value settles to 1e-6),
/// formed by running the recurrence twice instead of storing its basis: 2 max_steps
/// matrix-vector products at most. Certified, but only as tight as Gershgorin's bound
/// above; S lets a caller aim the vector at another matrix (SPEC 7's index dt^2 A + 2 dt C)
/// and bound that matrix's top from the same vector. `vector`: the unit Ritz vector;
/// `lanczos_steps`: the steps of one run. Any rows count (no dense shortcut).
EigenInterval unfactored_largest_eigenvalue(const SparseMatrix& A, Eigen::VectorXd* vector,
                                            int threads, int max_steps, double scale = 1,
                                            const Eigen::VectorXd* d = nullptr);

/// Smallest eigenvalue of symmetric A: the largest of -A, negated (lo certified by
/// Cholesky of A - lo I, hi the Rayleigh quotient). `floor`: a lower bound on lambda_min the
/// caller has proved (a splitting of A into a diagonal and positive semidefinite parts:
/// `psd_floor` in linear_stability.hpp); when the smallest diagonal entry, a Rayleigh
/// quotient, lies within the promised width of it, [floor - margin, that entry] is the
/// answer and nothing is factorised (a flat mesh at rest: its out-of-plane rows).
EigenInterval certified_smallest_eigenvalue(const SparseMatrix& A,
                                            std::optional<double> floor = std::nullopt,
                                            int threads = 1,
                                            double max_factor_flops = kNoFactorBudget);

/// Both ends at once (one dense solve up to 400 rows, else the two methods above).
struct CertifiedSpectrum {
  EigenInterval smallest;
  EigenInterval largest;
};
/// `within_budget`, when given, is called on the calling thread once the pattern analysis has
/// cleared the budget, before the first factorisation (or before the dense solve): work wanted
/// only when the ends are computed can start beside the factorisations then. Not called for
/// the zero matrix, which needs neither.
CertifiedSpectrum certified_spectrum(const SparseMatrix& A,
                                     std::optional<double> floor = std::nullopt, int threads = 1,
                                     double max_factor_flops = kNoFactorBudget,
                                     const std::function<void()>& within_budget = {});
/// The same, its factorisations left in `factors` (made here when empty): a caller that goes
/// on to factor matrices of A's pattern (the exact limits' searches) keeps the pattern
/// analysis and the factor's memory.
CertifiedSpectrum certified_spectrum(const SparseMatrix& A,
                                     std::unique_ptr<detail::ShiftedCholesky>& factors,
                                     std::optional<double> floor, int threads,
                                     double max_factor_flops,
                                     const std::function<void()>& within_budget);

namespace detail {
/// The rounding of a Rayleigh quotient q = uAu / uu whose products u_r (A u)_r were summed in
/// long double over `terms` - 1 rows (uAu, and abs_uAu the sum of their absolute values), each
/// (A u)_r in double over at most `row_nonzeros` entries of absolute sum at most
/// `abs_row_sum`: q less this is a lower bound of the exact quotient.
double rayleigh_rounding(long double uAu, long double abs_uAu, long double uu, long double terms,
                         int row_nonzeros, double abs_row_sum, double q);
}  // namespace detail

}  // namespace dampbound
