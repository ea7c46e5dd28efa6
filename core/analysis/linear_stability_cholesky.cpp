// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/linear_stability_cholesky.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "core/analysis/detail/beside.hpp"
#include "core/analysis/detail/inverse_lanczos.hpp"
#include "core/analysis/detail/lanczos.hpp"
#include "core/analysis/detail/shifted_cholesky.hpp"

namespace dampbound {

double detail::rayleigh_rounding(long double uAu, long double abs_uAu, long double uu,
                                 long double terms, int row_nonzeros, double abs_row_sum,
                                 double q) {
  // |fl(Au) - Au| <= k eps |A||u| per row (k nonzeros), and || |A| || <= max row sum of |A|.
  // The two long double sums of n products err by at most gamma_{n+1} of their absolute sums
  // (unit roundoff 2^-64; Higham, Accuracy and Stability, 2nd ed., eq. 3.4), which moves the
  // quotient by at most gamma_{n+1} (sum |u_i (Au)_i| + |u^T A u|) / u^T u; the division and
  // the conversion to double round once more each.
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const long double unit = std::numeric_limits<long double>::epsilon() / 2;
  const long double gamma = terms * unit / (1 - terms * unit);
  const double sums = static_cast<double>(2 * gamma * (abs_uAu + std::abs(uAu)) / uu);
  return 2 * (row_nonzeros + 2) * eps * abs_row_sum + sums + eps * std::abs(q);
}

using detail::Beside;
using detail::estimate_beside;
using detail::inverse_lanczos;
using detail::kAmdSlack;
using detail::kShortTolerance;
using detail::lanczos_estimate;
using detail::LanczosRecurrence;
using detail::resolved_threads;
using detail::ShiftedCholesky;
using detail::short_inverse_lanczos;
using detail::TopEstimate;
namespace {

/// Room above a shift, relative to max_r sum_s |A_rs|, so that a factorisation just above
/// lambda_max does not fail by rounding; what a success proves allows for its rounding
/// separately (ShiftedCholesky::proved_above).
constexpr double kMargin = 1e-12;
/// Up to this many rows the dense eigenvalues are cheaper than factorisations (a 10 x 10
/// plane, 300 rows: a few ms) and exact to rounding: lo = hi.
constexpr Eigen::Index kDenseRows = 400;

/// u^T A u / u^T u, summed in long double, and a bound on its rounding error.
struct Rayleigh {
  double value, residual, rounding;
};
Rayleigh rayleigh(const SparseMatrix& A, const Eigen::VectorXd& u, double abs_row_sum,
                  int row_nonzeros) {
  const Eigen::VectorXd Au = A * u;
  long double uAu = 0, uu = 0, abs_uAu = 0;
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    const long double p = static_cast<long double>(u(i)) * Au(i);
    uAu += p;
    abs_uAu += std::abs(p);
    uu += static_cast<long double>(u(i)) * u(i);
  }
  const double q = static_cast<double>(uAu / uu);
  const double rounding = detail::rayleigh_rounding(
      uAu, abs_uAu, uu, static_cast<long double>(u.size()) + 1, row_nonzeros, abs_row_sum, q);
  return {q, (Au - q * u).norm() / std::sqrt(static_cast<double>(uu)), rounding};
}

/// What both ends need from the rows of A: Gershgorin's discs, the largest row sum of |A|
/// and row count (the rounding allowances), the extreme diagonal entries (Rayleigh quotients
/// of unit vectors).
struct RowBounds {
  GershgorinBounds gershgorin;
  double abs_row_sum = 0;
  int row_nonzeros = 0;
  double min_diagonal = std::numeric_limits<double>::infinity();
  double max_diagonal = -std::numeric_limits<double>::infinity();
  double margin() const { return kMargin * abs_row_sum; }
};
RowBounds row_bounds(const SparseMatrix& A) {
  RowBounds b;
  if (A.rows() == 0) return b;
  b.gershgorin = {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (int k = 0; k < A.outerSize(); ++k) {  // symmetric: columns are rows
    double sum = 0, diagonal = 0, off = 0;
    int count = 0;
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
      sum += std::abs(it.value());
      ++count;
      if (it.row() == k)
        diagonal += it.value();
      else
        off += std::abs(it.value());
    }
    b.gershgorin.lo = std::min(b.gershgorin.lo, diagonal - off);
    b.gershgorin.hi = std::max(b.gershgorin.hi, diagonal + off);
    b.abs_row_sum = std::max(b.abs_row_sum, sum);
    b.row_nonzeros = std::max(b.row_nonzeros, count);
    b.min_diagonal = std::min(b.min_diagonal, diagonal);
    b.max_diagonal = std::max(b.max_diagonal, diagonal);
  }
  return b;
}

/// How far above the Rayleigh quotient `value` the certificate is tried (units of A): the
/// promised width of the interval, ~1e-10 relative.
double certificate_width(double value, double span) {
  return 1e-10 * std::abs(value) + 1e-11 * span;
}

}  // namespace

GershgorinBounds gershgorin_bounds(const SparseMatrix& A) { return row_bounds(A).gershgorin; }

namespace {
std::string over_budget_text(double flops, double bytes, double budget, bool amd_only) {
  char text[240];
  if (amd_only)
    std::snprintf(text, sizeof text,
                  "one factorisation would take %.3g GFlop and %.3g GB in AMD's ordering "
                  "(a quick estimate; nested dissection saved 7.5x on a 1M-node block), over "
                  "%.0f times the budget of %.3g GFlop",
                  flops / 1e9, bytes / 1e9, kAmdSlack, budget / 1e9);
  else
    std::snprintf(text, sizeof text,
                  "one factorisation would take %.3g GFlop and %.3g GB, over the budget of %.3g "
                  "GFlop",
                  flops / 1e9, bytes / 1e9, budget / 1e9);
  return text;
}
}  // namespace

FactorisationOverBudget::FactorisationOverBudget(double flops_, double bytes_, double budget_,
                                                 bool amd_only_)
    : std::runtime_error(over_budget_text(flops_, bytes_, budget_, amd_only_)),
      flops(flops_),
      bytes(bytes_),
      budget(budget_),
      amd_only(amd_only_) {}

namespace {

/// certified_largest_eigenvalue with its factorisations in `held`: made for A when empty, else
/// given A's values (ShiftedCholesky::assign), which keeps the pattern analysis when A has the
/// pattern analysed before. certified_spectrum holds one for both ends: -A has A's pattern, and
/// the analysis (the fill-reducing ordering) depends on the pattern alone, so the bottom end
/// factors in the same order, to the same bits, without a second analysis.
///
/// `given`: the Lanczos estimate of A, already made (certified_spectrum makes the bottom end's
/// beside the top end's factorisations). `after_estimate`: called once the estimate is done
/// and the rest, one core's CHOLMOD work, begins.
EigenInterval largest(const SparseMatrix& A, std::unique_ptr<ShiftedCholesky>& held,
                      Eigen::VectorXd* vector, int threads, double max_factor_flops,
                      const TopEstimate* given = nullptr,
                      const std::function<void()>& after_estimate = {}) {
  const Eigen::Index n = A.rows();
  if (n == 0) return {};
  if (n <= kDenseRows) {  // small: the dense eigenvalues are exact, and quicker
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{
        Eigen::MatrixXd(A), vector ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly};
    if (vector) *vector = es.eigenvectors().col(n - 1);
    const double value = es.eigenvalues()(n - 1);
    return {value, value};
  }
  const RowBounds rows = row_bounds(A);
  const GershgorinBounds g = rows.gershgorin;
  const double abs_row_sum = rows.abs_row_sum;
  const int row_nonzeros = rows.row_nonzeros;
  if (abs_row_sum == 0) {  // the zero matrix
    if (vector) *vector = Eigen::VectorXd::Unit(n, 0);
    return {};
  }
  const double span = g.hi - g.lo, margin = rows.margin();
  EigenInterval out;
  const int factorizations_before = held ? held->factorizations : 0;
  const int solves_before = held ? held->solves : 0;
  // The factorisations' matrix and its pattern analysis, beside the Lanczos estimate (below).
  const auto prepare = [&] {
    if (held)
      held->assign(A);
    else
      held = std::make_unique<ShiftedCholesky>(A);
    held->analyse(max_factor_flops);
  };
  const int cores = resolved_threads(threads);
  // The top of a big mesh's spectrum is clustered: only a shift close above lambda_max
  // separates it from the rest. A Lanczos estimate places the shift (below). On two or more
  // threads one of them prepares the factorisations meanwhile (the two share nothing:
  // ShiftedCholesky holds its own copy of the matrix), and the estimate takes it back when
  // that is done; over the budget the estimate stops there, so the answer is as quick as
  // before. Lanczos gives the same bits on any thread count.
  const TopEstimate estimate = [&] {
    if (given) {
      prepare();
      return *given;
    }
    if (cores < 2) {
      prepare();
      LanczosRecurrence<float> lanczos(A, cores);
      return lanczos_estimate(lanczos, n);
    }
    Beside preparing(prepare);
    const TopEstimate e = estimate_beside(
        A, cores, [&] { return preparing.done(); },
        [&] { return preparing.done() && preparing.failed(); });  // over the budget: stop
    preparing.finish();
    return e;
  }();
  if (after_estimate) after_estimate();
  ShiftedCholesky& f = *held;
  f.set_solve_threads(cores);
  Eigen::VectorXd u;
  // Gershgorin: lambda_max <= g.hi, so (g.hi + a little) I - A is positive definite; the
  // largest diagonal entry (a Rayleigh quotient) is below lambda_max.
  const double gershgorin = g.hi + 1e-6 * span + margin;
  double up = gershgorin;
  const double max_diagonal = rows.max_diagonal;
  // The first shift lies four times the estimate's extrapolated error above its Ritz value.
  // A factorisation that fails says the shift is still below lambda_max (Lanczos can stall
  // on an eigenvalue just under the top): the next shift is twice the residual above (some
  // eigenvalue lies within it), then eightfold steps, at worst up to Gershgorin's bound.
  // Both allow for the estimate's matrix (A in float) lying up to its matrix_error from A.
  const double wide = std::max(2 * estimate.residual, 1e-9 * span);
  const double fallback = wide + estimate.matrix_error;
  double step = std::clamp(4 * estimate.error, 1e-9 * span, wide) + estimate.matrix_error;
  // The shift of the first factorisation that succeeds. What it proves (its rounding bound, a
  // pass over the factor) lies above the shift, so it is taken only where it can matter.
  std::optional<double> first_shift;
  for (;;) {
    const double s = estimate.theta + step + margin;
    if (!(s < gershgorin)) break;  // NaN too: no estimate (T not finite), Gershgorin's shift
    if (f.factor(s)) {
      first_shift = s;
      break;
    }
    step = f.factorizations - factorizations_before == 1 ? std::max(fallback, 8 * step) : 8 * step;
  }
  if (!f.ready() && !f.factor(gershgorin)) {
    // Rounding trouble even at Gershgorin's shift: his bound alone, and the diagonal.
    out.certified = false;
    out.lo = max_diagonal;
    out.hi = g.hi;
    u = Eigen::VectorXd::Unit(n, 0);
  } else {
    if (!short_inverse_lanczos(f, detail::lanczos_start(n), u, kShortTolerance))
      inverse_lanczos(f, u, 1e-10);
    const Rayleigh q = rayleigh(A, u, abs_row_sum, row_nonzeros);
    const double lo = std::max(max_diagonal, q.value - q.rounding);
    // The certificate: a factorisation just above the Rayleigh quotient, tried where the
    // interval is wider than its width, which min(up, first factorisation's bound) decides.
    // That bound exceeds the first shift: where the shift alone says "wider", the bound is
    // needed only if the certificate fails or proves more than the shift, and then the first
    // shift is factored again (the same bits) to take it.
    const double width = certificate_width(q.value, span), room = width + 2 * margin;
    const auto take_first = [&] {
      if (!f.ready() || f.shift() != *first_shift) f.factor(*first_shift);
      up = std::min(up, f.proved_above());
      first_shift.reset();
    };
    if (first_shift && std::min(up, *first_shift) - lo <= room) take_first();
    if (up - lo > room && (!first_shift || std::min(up, *first_shift) - lo > room)) {
      const bool certified = f.factor(lo + width + margin);
      const double proved = certified ? f.proved_above() : up;
      if (first_shift && (!certified || proved > *first_shift)) take_first();
      up = std::min(up, proved);
    }
    out.lo = lo;
    out.hi = up;
  }
  out.factorizations = f.factorizations - factorizations_before;
  out.solves = f.solves - solves_before;
  out.lanczos_steps = estimate.steps;
  if (vector) *vector = u / u.norm();
  return out;
}

/// A known lower bound of lambda_min (e.g. a splitting of A into positive semidefinite parts)
/// and the smallest diagonal entry (a Rayleigh quotient) may already pin lambda_min down: the
/// interval they give when they lie within the certificate's width.
std::optional<EigenInterval> pinned_by_floor(const SparseMatrix& A, std::optional<double> floor) {
  if (!floor || A.rows() <= kDenseRows) return std::nullopt;
  const RowBounds rows = row_bounds(A);
  const double lo = *floor - rows.margin(), hi = rows.min_diagonal;
  const double span = rows.gershgorin.hi - rows.gershgorin.lo;
  if (lo <= hi && hi - lo <= certificate_width(hi, span) + 2 * rows.margin())
    return EigenInterval{lo, hi};
  return std::nullopt;
}

/// lambda_min of A from lambda_max of `negated` = -A (largest() says how, `given` included).
EigenInterval smallest_of_negated(const SparseMatrix& negated,
                                  std::unique_ptr<ShiftedCholesky>& held, int threads,
                                  double max_factor_flops, const TopEstimate* given = nullptr) {
  EigenInterval r = largest(negated, held, nullptr, threads, max_factor_flops, given);
  std::swap(r.lo, r.hi);
  r.lo = -r.lo;
  r.hi = -r.hi;
  return r;
}

/// certified_smallest_eigenvalue with its factorisations in `held` (largest() says how).
EigenInterval smallest(const SparseMatrix& A, std::optional<double> floor,
                       std::unique_ptr<ShiftedCholesky>& held, int threads,
                       double max_factor_flops) {
  if (const std::optional<EigenInterval> pinned = pinned_by_floor(A, floor)) return *pinned;
  return smallest_of_negated(-A, held, threads, max_factor_flops);
}

}  // namespace

EigenInterval certified_largest_eigenvalue(const SparseMatrix& A, Eigen::VectorXd* vector,
                                           int threads, double max_factor_flops) {
  std::unique_ptr<ShiftedCholesky> factors;
  return largest(A, factors, vector, threads, max_factor_flops);
}

EigenInterval certified_largest_eigenvalue(const SparseMatrix& A,
                                           std::unique_ptr<ShiftedCholesky>& factors, int threads,
                                           double max_factor_flops, Eigen::VectorXd* vector) {
  return largest(A, factors, vector, threads, max_factor_flops);
}

EigenInterval unfactored_largest_eigenvalue(const SparseMatrix& A, Eigen::VectorXd* vector,
                                            int threads, int max_steps, double scale,
                                            const Eigen::VectorXd* d) {
  const Eigen::Index n = A.rows();
  EigenInterval out;
  out.factorizations = 0;
  if (n == 0 || max_steps < 1) {
    out.lo = -std::numeric_limits<double>::infinity();
    out.hi = std::numeric_limits<double>::infinity();
    return out;
  }
  const RowBounds rows = row_bounds(A);
  out.hi = rows.gershgorin.hi;
  // Lanczos on S, its top Ritz value settled to 1e-6 in windows of kUnfactoredCheck steps or
  // max_steps reached; then T's top eigenvector y and, replaying the same recurrence, the
  // Ritz vector u = sum_j y_j v_j.
  constexpr int kUnfactoredCheck = 10;
  const TopEstimate e = [&] {
    LanczosRecurrence<double> lanczos(A, threads, scale, d);
    return lanczos_estimate(lanczos, n, max_steps, kUnfactoredCheck, 1e-6);
  }();
  const int m = e.steps;
  std::vector<double> y = e.y;
  if (y.empty()) y = {1.0};  // inverse iteration broke down: the start vector itself
  LanczosRecurrence<double> replay(A, threads, scale, d);
  Eigen::VectorXd u = y[0] * replay.vector();
  // The first run took these steps without meeting an invariant subspace, and the replay
  // makes the same operations.
  for (size_t j = 1; j < y.size() && replay.step(); ++j) u += y[j] * replay.vector();
  const Rayleigh q = rayleigh(A, u, rows.abs_row_sum, rows.row_nonzeros);
  out.lo = q.value - q.rounding;
  out.lanczos_steps = m;
  if (vector) *vector = u / u.norm();
  return out;
}

CertifiedSpectrum certified_spectrum(const SparseMatrix& A, std::optional<double> floor,
                                     int threads, double max_factor_flops,
                                     const std::function<void()>& within_budget) {
  std::unique_ptr<ShiftedCholesky> factors;
  return certified_spectrum(A, factors, floor, threads, max_factor_flops, within_budget);
}

CertifiedSpectrum certified_spectrum(const SparseMatrix& A,
                                     std::unique_ptr<ShiftedCholesky>& factors,
                                     std::optional<double> floor, int threads,
                                     double max_factor_flops,
                                     const std::function<void()>& within_budget) {
  const Eigen::Index n = A.rows();
  if (n > 0 && n <= kDenseRows) {  // one dense solve gives both ends
    if (within_budget) within_budget();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(A), Eigen::EigenvaluesOnly};
    const double lo = es.eigenvalues()(0), hi = es.eigenvalues()(n - 1);
    return {{lo, lo}, {hi, hi}};
  }
  // The top first: over a budget it stops before the bottom copies -A. One pattern analysis
  // serves both ends.
  const int cores = resolved_threads(threads);
  if (cores < 2 || pinned_by_floor(A, floor)) {
    const EigenInterval top =
        largest(A, factors, nullptr, threads, max_factor_flops, nullptr, within_budget);
    return {smallest(A, floor, factors, threads, max_factor_flops), top};
  }
  // On two or more threads the bottom end's Lanczos estimate (of -A) runs beside the top end's
  // factorisations and solves, which keep one core: it starts once the top's own estimate is
  // done, on the other threads, and takes them all once the top is done. Lanczos gives the
  // same bits on any thread count, so both ends are the bits of one thread.
  SparseMatrix negated;
  TopEstimate bottom;
  std::atomic<bool> top_done{false}, stop{false};
  std::unique_ptr<Beside> estimating;  // after what it uses: destroyed (joined) first
  const auto start_bottom = [&] {
    if (within_budget) within_budget();
    estimating = std::make_unique<Beside>([&] {
      negated = -A;
      bottom = estimate_beside(
          negated, cores, [&] { return top_done.load(std::memory_order_acquire); },
          [&] { return stop.load(std::memory_order_relaxed); });
    });
  };
  EigenInterval top;
  try {
    top = largest(A, factors, nullptr, threads, max_factor_flops, nullptr, start_bottom);
  } catch (...) {
    stop.store(true, std::memory_order_relaxed);  // and the destructor joins it
    throw;
  }
  top_done.store(true, std::memory_order_release);
  if (!estimating)  // the top needed no estimate (the zero matrix)
    return {smallest(A, floor, factors, threads, max_factor_flops), top};
  estimating->finish();
  return {smallest_of_negated(negated, factors, threads, max_factor_flops, &bottom), top};
}

EigenInterval certified_smallest_eigenvalue(const SparseMatrix& A, std::optional<double> floor,
                                            int threads, double max_factor_flops) {
  std::unique_ptr<ShiftedCholesky> factors;
  return smallest(A, floor, factors, threads, max_factor_flops);
}

}  // namespace dampbound
