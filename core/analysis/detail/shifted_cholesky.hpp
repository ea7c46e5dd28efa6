#pragma once
// Factorisations of sigma I - A for a changing shift sigma (SPEC 7, 9), by CHOLMOD's
// supernodal Cholesky, for certified_largest_eigenvalue (linear_stability_cholesky.cpp): the
// pattern analysed once, each shift one numeric factorisation, solves with the factor, and
// what a successful factorisation proves allowing for its rounding (cholesky_rounding.hpp).
// Every call into CHOLMOD takes the one turn of the process (shifted_cholesky.cpp says why).
#include <Eigen/CholmodSupport>
#include <vector>

#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
#include "core/analysis/detail/supernodal_solve.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"

namespace dampbound::detail {

/// Above this many rows a budget is first checked against AMD's ordering alone (of the
/// nodes, when the rows come in threes): CHOLMOD's default analysis also tries METIS and
/// nested dissection, which on a million-node mesh costs many times AMD alone. AMD's flop
/// prediction runs up to about 17x above the better ordering's on tetrahedral blocks
/// (docs/performance.md), so only a prediction kAmdSlack times over the budget stops the
/// analysis there.
inline constexpr Eigen::Index kQuickCheckRows = 500000;
inline constexpr double kAmdSlack = 32;

/// Eigen's wrapper of CHOLMOD's supernodal LL', with the factor in view (for its rounding).
class SupernodalLLT : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
 public:
  const cholmod_factor& factor() const { return *m_cholmodFactor; }
  cholmod_factor& factor() { return *m_cholmodFactor; }
};

/// Factorisations of sigma I - A for a changing shift sigma, by CHOLMOD's supernodal
/// Cholesky (fill-reducing ordering chosen by CHOLMOD: AMD or nested dissection): the
/// pattern is analysed once; each shift is one numeric factorisation of -A + sigma I.
/// CHOLMOD's own OpenMP loops run as teams of one (detail/serial_openmp.hpp).
///
/// Rows of A with no entry off the diagonal (a flat mesh's out-of-plane rows at rest) stay out
/// of CHOLMOD's factorisation: each is an eigenvalue of A, its diagonal entry d, exactly, and
/// sigma - d > 0 is decided exactly in floating point (a difference has the sign of the exact
/// one), so the shift is a certificate for them with no rounding to allow for. CHOLMOD would
/// make each a supernode of one column, with its fixed cost per supernode (its OpenMP regions,
/// its BLAS calls): on the 200 x 200 plane 40 000 of 47 496.
class ShiftedCholesky {
 public:
  /// `cholmod_ordering`: CHOLMOD's own choice of ordering at every size (AMD, then METIS
  /// where AMD's fill is poor), for callers that factor one pattern many times; otherwise AMD
  /// alone below 20 000 rows (shifted_cholesky.cpp).
  explicit ShiftedCholesky(const SparseMatrix& A, bool cholmod_ordering = false);
  /// Whether the ordering is CHOLMOD's own choice (asked for, or at this size anyway): the
  /// pattern analysis a ShiftedCholesky(A, true) of the same pattern would make.
  bool cholmod_ordering() const { return cholmod_ordering_; }
  /// The pattern analysis (once); throws FactorisationOverBudget when one numeric
  /// factorisation would take more than `budget` flops. Within the budget it also allocates
  /// the factor's values and touches their pages, which the first factorisation would
  /// otherwise do: certified_largest_eigenvalue analyses beside its estimate, so that work
  /// leaves the critical path.
  void analyse(double budget);
  /// Factors sigma I - A; true when it is positive definite (every pivot > 0).
  bool factor(double sigma);
  /// Takes the values of another A of the same pattern (a Newton step's next tangent
  /// stiffness), keeping the pattern analysis; another pattern is analysed anew.
  void assign(const SparseMatrix& A);
  /// After a successful factor(sigma): what it proves, lambda_max(A) < the result, allowing
  /// for the factorisation's rounding (detail/cholesky_rounding.hpp), rounded up.
  double proved_above() const;
  bool ready() const { return ok_; }
  /// out = (sigma I - A)^-1 in after a successful factor(sigma) (detail/supernodal_solve.hpp):
  /// on a big factor the elimination tree's two halves at once, on `solve_threads` (the same
  /// bits on one thread or two).
  void solve(const double* in, double* out);
  void set_solve_threads(int threads) { solve_threads_.set_threads(threads); }
  Eigen::Index size() const { return n_; }
  /// The rows CHOLMOD factors (the others have no entry off the diagonal).
  Eigen::Index factored_rows() const { return B_.rows(); }
  /// The shift of the last factor() call.
  double shift() const { return sigma_; }
  int factorizations = 0, solves = 0;

 private:
  /// Splits A into the rows alone (lone_, with their diagonal entries) and the rest, whose
  /// lower triangle of -A goes to B; true when the split is the one held (same pattern).
  bool split(const SparseMatrix& A, SparseMatrix& B);
  void solve_factored(const double* in, double* out);
  Eigen::Index n_;
  SparseMatrix B_;                     ///< -A's lower triangle on the factored rows
  std::vector<int> factored_;          ///< A's row of each row of B_ (empty: every row, in order)
  std::vector<int> lone_;              ///< A's rows with no entry off the diagonal
  std::vector<double> lone_diagonal_;  ///< their A_kk (0 where A has no entry)
  std::vector<double> gathered_in_, gathered_out_;
  void allocate_values();
  SupernodalLLT llt_;
  std::vector<double> solve_work_;
  SolveSplit split_;  ///< from the pattern, made beside the first factorisation; empty: serial
  bool split_ready_ = false;
  NodeThreads solve_threads_;
  double sigma_ = 0;
  bool analysed_ = false, ok_ = false;
  /// The pattern analysis's prediction for one factorisation (checked against each caller's
  /// budget, also where the analysis was an earlier caller's).
  double predicted_flops_ = 0, predicted_bytes_ = 0;
  bool cholmod_ordering_ = true;
};

}  // namespace dampbound::detail
