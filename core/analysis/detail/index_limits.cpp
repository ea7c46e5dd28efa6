// The paper's step at non-uniform nodal rates (linear_stability_exact.cpp's symmetric_index
// route): the certified definiteness index at the scene and its roots in gamma and dt.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/index_limits.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/analysis/detail/definite_root.hpp"
#include "core/analysis/detail/shifted_cholesky.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/physics/detail/numbers.hpp"
#include "core/physics/integrate.hpp"
#include "dampbound/physics/closed_forms.hpp"

namespace dampbound::detail {
namespace {

/// lambda_max(h^2 A + 2 h gamma diag(R)), certified (its upper end); on `factors`, which
/// keeps their pattern analysis between calls (every such matrix has one pattern).
double symmetric_index(const SparseMatrix& A, const Eigen::VectorXd& R, double gamma, double h,
                       int threads, double budget, std::unique_ptr<ShiftedCholesky>& factors) {
  SparseMatrix S = (h * h) * A;
  for (Eigen::Index i = 0; i < S.rows(); ++i) S.coeffRef(i, i) += 2 * h * gamma * R(i);
  return certified_largest_eigenvalue(S, factors, threads, budget).hi;
}

/// Whether the certified index without damping, lambda_max(h^2 A), reaches 4. That is h^2
/// times A's lambda_max, whose certified interval [lambda_max_lo, spectrum.lambda_max] is
/// already known: below 4 (1 - 1e-8) or above 4 (1 + 1e-12) it decides as the certified index
/// of h^2 A does (an interval about 1e-10 wide above the same eigenvalue, entries rounded
/// once), without its factorisations; in between, or where A's interval is wider, that index
/// is computed as before.
bool undamped_index_reaches_4(const SparseMatrix& A, const Eigen::VectorXd& R, double h,
                              const ExactStability& e, int threads, double budget,
                              std::unique_ptr<ShiftedCholesky>& factors) {
  const double lo = h * h * e.lambda_max_lo, hi = h * h * e.spectrum.lambda_max;
  const bool narrow = hi - lo <= 1e-9 * hi;
  if (narrow && lo > 4 * (1 + 1e-12)) return true;
  if (narrow && hi < 4 * (1 - 1e-8)) return false;
  return symmetric_index(A, R, 0, h, threads, budget, factors) >= 4;
}

/// The gamma and dt limits of symmetric_index_limits.
void limit_searches(const ExactInputs& in, const Params& params, const ExactOptions& options,
                    ExactStability& e, std::unique_ptr<ShiftedCholesky>& factors) {
  const int threads = options.threads;
  const double budget = options.max_factor_flops;
  const double h = params.dt, gamma = params.gamma;
  const SparseMatrix& A = in.A;
  const Eigen::VectorXd& R = in.R;
  // Each limit is the largest value at which 4 I - S is proved positive definite, S the
  // index matrix (detail/definite_root.hpp: a few factorisations on one pattern analysis).
  SparseMatrix Rd(A.rows(), A.cols());
  {
    std::vector<Eigen::Triplet<double>> diagonal;
    for (Eigen::Index i = 0; i < R.size(); ++i) diagonal.emplace_back(i, i, R(i));
    Rd.setFromTriplets(diagonal.begin(), diagonal.end());
  }
  // gamma: S(t) = h^2 A + 2 h t diag(R), linear in t; 0 where t = 0 is already unstable.
  if (undamped_index_reaches_4(A, R, h, e, threads, budget, factors)) {
    e.gamma_hi = 0;
  } else {
    const SparseMatrix base = (h * h) * A, step = (2 * h) * Rd;
    IndexFamily family;
    family.S = [&](double t) -> SparseMatrix { return base + t * step; };
    family.D = [&](double) -> SparseMatrix { return step; };
    e.gamma_hi = definite_root(family, 0, &factors, budget).stable;
  }
  // dt: S(t) = t^2 A + 2 t gamma diag(R), from the scene's dt.
  double cap = spec7_dt_max_undamped(e.spectrum.lambda_max);
  if (gamma * in.r_max > 0) cap = std::min(cap, 2 / (gamma * in.r_max));
  if (std::isinf(cap)) {
    e.dt_max = kInf;
  } else {
    const SparseMatrix C = gamma * Rd;
    IndexFamily family;
    family.S = [&](double t) -> SparseMatrix { return (t * t) * A + (2 * t) * C; };
    family.D = [&](double t) -> SparseMatrix { return (2 * t) * A + 2.0 * C; };
    family.Q = A;
    e.dt_max = definite_root(family, h, &factors, budget).stable;
  }
}

}  // namespace

/// The paper's step with non-uniform rates: the exact definiteness index (SPEC 7) and its
/// roots in gamma and in dt, each proved stable within 1e-10 relative of a value not proved so.
void symmetric_index_limits(const ExactInputs& in, const Params& params,
                            const ExactOptions& options, ExactStability& e,
                            std::unique_ptr<ShiftedCholesky>& factors) {
  const int threads = options.threads;
  const double budget = options.max_factor_flops;
  const double h = params.dt, gamma = params.gamma;
  const SparseMatrix& A = in.A;
  const Eigen::VectorXd& R = in.R;
  e.method = ExactMethod::symmetric_index;
  e.gamma_lo = 0;
  // Every matrix below has the pattern of A and its diagonal: one pattern analysis (CHOLMOD's
  // choice of ordering; the spectrum's where it made one), for them and for the index at the
  // scene.
  if (!e.indefinite) limit_searches(in, params, options, e, factors);
  e.index = symmetric_index(A, R, gamma, h, threads, budget, factors);
  e.stable = e.index < 4 && in.r_min > 0;
}

}  // namespace dampbound::detail
