#pragma once
// Factorisations of sigma I - A for a changing shift sigma (SPEC 7, 9), by CHOLMOD's
// supernodal Cholesky, for certified_largest_eigenvalue (linear_stability_cholesky.cpp): the
// pattern analysed once, each shift one numeric factorisation, solves with the factor, and
// what a successful factorisation proves allowing for its rounding (cholesky_rounding.hpp).
// Every call into CHOLMOD takes the one turn of the process (shifted_cholesky.cpp says why).
#include <Eigen/CholmodSupport>
#include <vector>

#include "core/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
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
class ShiftedCholesky {
 public:
  explicit ShiftedCholesky(const SparseMatrix& A);
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
  /// The shift of the last factor() call.
  double shift() const { return sigma_; }
  int factorizations = 0, solves = 0;

 private:
  Eigen::Index n_;
  SparseMatrix B_;
  void allocate_values();
  SupernodalLLT llt_;
  std::vector<double> solve_work_;
  SolveSplit split_;  ///< from the pattern, made beside the first factorisation; empty: serial
  bool split_ready_ = false;
  NodeThreads solve_threads_;
  double sigma_ = 0;
  bool analysed_ = false, ok_ = false;
};

}  // namespace dampbound::detail
