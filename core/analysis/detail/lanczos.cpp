// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/lanczos.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "core/analysis/detail/symmetric_product.hpp"
#include "core/analysis/detail/tridiagonal.hpp"

namespace dampbound::detail {

Eigen::VectorXd lanczos_start(Eigen::Index n) {
  Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(n, 0.3, 1.7).array().sin();
  for (Eigen::Index i = 3; i < n; i += 6) v.segment(i, std::min<Eigen::Index>(3, n - i)) *= -1;
  return v / v.norm();
}

template <class Scalar>
LanczosRecurrence<Scalar>::LanczosRecurrence(const SparseMatrix& A, int threads, double scale,
                                             const Eigen::VectorXd* d)
    : A_(A), d_(d), scale_(scale), pool_(threads) {
  // One product follows another after a few vector passes (about 0.1 ms at 40k nodes): the
  // workers poll for it rather than sleep (docs/performance.md, "Lanczos's products on
  // threads").
  pool_.set_spin_microseconds(kLanczosSpinMicroseconds);
  // The passes run over blocks of rows (detail/symmetric_product.hpp): the pool's grain in
  // blocks, the rows per thread as for any other loop.
  pool_.set_grain(NodeThreads::kMinItemsPerThread / kSumBlockRows);
  const Eigen::VectorXd start = lanczos_start(A.rows());
  if constexpr (std::is_same_v<Scalar, float>) {
    if (d || scale != 1) throw std::invalid_argument("single-precision Lanczos: S = A only");
    const Eigen::Index nonzeros = A.outerIndexPtr()[A.outerSize()];
    single_.resize(static_cast<size_t>(nonzeros));
    const double* value = A.valuePtr();
    // |fl(a) - a| <= 2^-24 |a| + 2^-150 (the second term below float's normal range); a
    // value beyond its largest (or not finite) makes the bound infinite, which widens the
    // first shift to Gershgorin's.
    double worst_row = 0;
    int worst_count = 0;
    bool in_range = true;
    for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
      const int first = A.outerIndexPtr()[c];
      const int last =
          A.innerNonZeroPtr() ? first + A.innerNonZeroPtr()[c] : A.outerIndexPtr()[c + 1];
      double row = 0;
      for (int k = first; k < last; ++k) {
        const double a = std::abs(value[k]);
        in_range = in_range && a <= std::numeric_limits<float>::max();  // false for NaN
        single_[static_cast<size_t>(k)] = static_cast<float>(value[k]);
        row += a;
      }
      worst_row = std::max(worst_row, row);
      worst_count = std::max(worst_count, last - first);
    }
    matrix_error_ = in_range
                        ? (std::ldexp(worst_row, -24) + std::ldexp(worst_count, -150)) * (1 + 1e-6)
                        : std::numeric_limits<double>::infinity();
    v_ = start.cast<float>();
  } else {
    v_ = start;
  }
  previous_ = Vector::Zero(A.rows());
}

template <class Scalar>
bool LanczosRecurrence<Scalar>::step() {
  double a;
  if constexpr (std::is_same_v<Scalar, float>)
    a = product_and_dot(SingleOperator{A_, single_.data()}, v_, static_cast<float>(b_), previous_,
                        w_, partial_, pool_);
  else
    a = product_and_dot({A_, scale_, d_}, v_, b_, previous_, w_, partial_, pool_);
  alpha.push_back(a);
  b_ = std::sqrt(subtract_and_square(w_, static_cast<Scalar>(a), v_, partial_, pool_));
  beta.push_back(b_);
  if (!(b_ > 0)) return false;
  previous_.swap(v_);
  divide(w_, static_cast<Scalar>(b_), v_, pool_);
  return true;
}

template class LanczosRecurrence<double>;
template class LanczosRecurrence<float>;

template <class Scalar>
TopEstimate lanczos_estimate(LanczosRecurrence<Scalar>& lanczos, Eigen::Index n, int max_steps,
                             int check, double tolerance, const std::function<bool()>& after_step) {
  const int k = static_cast<int>(std::min<Eigen::Index>(max_steps, n));
  std::vector<double> checkpoints;  // top Ritz value every `check` steps
  TopEstimate e;
  for (int j = 0; j < k; ++j) {
    if (!lanczos.step()) break;
    if (after_step && !after_step()) break;
    if ((j + 1) % check != 0) continue;
    checkpoints.push_back(
        largest_tridiagonal_eigenvalue(lanczos.alpha.data(), lanczos.beta.data(), j + 1));
    const size_t c = checkpoints.size();
    if (c < 3) continue;
    const double rise = checkpoints[c - 1] - checkpoints[c - 2];
    const double before = checkpoints[c - 2] - checkpoints[c - 3];
    const double q = before > 0 ? std::clamp(rise / before, 0.5, 0.9) : 0.9;
    e.error = std::max(rise, 0.0) * q / (1 - q);
    if (e.error < tolerance * std::abs(checkpoints[c - 1])) break;
  }
  const int m = static_cast<int>(lanczos.alpha.size());
  TridiagonalTop top = tridiagonal_top(lanczos.alpha.data(), lanczos.beta.data(), m);
  e.theta = top.value;
  e.steps = m;
  // The Ritz pair's residual: beta_m times the last component of its eigenvector of T.
  e.residual = top.vector.empty() ? std::numeric_limits<double>::quiet_NaN()
                                  : std::abs(lanczos.beta.back()) * std::abs(top.vector.back());
  e.y = std::move(top.vector);
  if (!std::isfinite(e.residual)) e.residual = std::abs(e.theta);  // no estimate: be wide
  if (checkpoints.size() < 3) e.error = e.residual;  // too few steps to extrapolate
  e.matrix_error = lanczos.matrix_error();
  e.alpha = lanczos.alpha;
  e.beta = lanczos.beta;
  return e;
}

template TopEstimate lanczos_estimate(LanczosRecurrence<double>&, Eigen::Index, int, int, double,
                                      const std::function<bool()>&);
template TopEstimate lanczos_estimate(LanczosRecurrence<float>&, Eigen::Index, int, int, double,
                                      const std::function<bool()>&);

}  // namespace dampbound::detail
