#include "core/analysis/detail/tridiagonal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dampbound::detail {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// max_i (|alpha_i| + |beta_i-1| + |beta_i|): a bound on every |eigenvalue| (Gershgorin).
double norm_bound(const double* alpha, const double* beta, int m) {
  double bound = 0;
  for (int i = 0; i < m; ++i)
    bound = std::max(bound, std::abs(alpha[i]) + (i > 0 ? std::abs(beta[i - 1]) : 0.0) +
                                (i + 1 < m ? std::abs(beta[i]) : 0.0));
  return bound;
}

}  // namespace

int eigenvalues_below(const double* alpha, const double* beta, int m, double x) {
  // Sylvester's law of inertia: the pivots d_i of T - x I = L D L^T,
  // d_0 = alpha_0 - x, d_i = alpha_i - x - beta_{i-1}^2 / d_{i-1}; a zero pivot is nudged
  // below zero by a rounding-sized amount (the count of an x within rounding of an
  // eigenvalue may go either way, which bisection tolerates).
  const double tiny = kEps * (norm_bound(alpha, beta, m) + std::abs(x)) + 1e-300;
  int count = 0;
  double d = 1;
  for (int i = 0; i < m; ++i) {
    d = alpha[i] - x - (i > 0 ? beta[i - 1] * beta[i - 1] / d : 0.0);
    if (d == 0) d = -tiny;
    if (d < 0) ++count;
  }
  return count;
}

double largest_tridiagonal_eigenvalue(const double* alpha, const double* beta, int m) {
  const double bound = norm_bound(alpha, beta, m);
  if (bound == 0) return 0;
  // Invariant: fewer than m eigenvalues below lo, all m below hi.
  double lo = -bound * (1 + 4 * kEps), hi = bound * (1 + 4 * kEps);
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi || hi - lo <= 2 * kEps * std::max(std::abs(lo), std::abs(hi)))
      break;
    if (eigenvalues_below(alpha, beta, m, mid) == m)
      hi = mid;
    else
      lo = mid;
  }
  return 0.5 * (lo + hi);
}

double last_eigenvector_component(const double* alpha, const double* beta, int m, double theta) {
  if (m == 1) return 1;
  const std::vector<double> z = tridiagonal_eigenvector(alpha, beta, m, theta);
  return z.empty() ? std::numeric_limits<double>::quiet_NaN() : std::abs(z.back());
}

std::vector<double> tridiagonal_eigenvector(const double* alpha, const double* beta, int m,
                                            double theta) {
  if (m == 1) return {1.0};
  const double tiny = kEps * (norm_bound(alpha, beta, m) + std::abs(theta)) + 1e-300;
  std::vector<double> z(static_cast<size_t>(m), 1.0);
  std::vector<double> d(static_cast<size_t>(m)), dl(static_cast<size_t>(m - 1)),
      du(static_cast<size_t>(m - 1));
  for (int step = 0; step < 3; ++step) {
    // Solve (T - theta I) z_new = z: elimination with row interchanges (LAPACK's dgtsv);
    // dl ends up holding the second superdiagonal that interchanges create.
    for (int i = 0; i < m; ++i) d[static_cast<size_t>(i)] = alpha[i] - theta;
    std::copy(beta, beta + m - 1, dl.begin());
    std::copy(beta, beta + m - 1, du.begin());
    for (size_t i = 0; i + 1 < static_cast<size_t>(m); ++i) {
      if (std::abs(d[i]) >= std::abs(dl[i])) {  // no interchange
        if (d[i] == 0) d[i] = tiny;
        const double f = dl[i] / d[i];
        d[i + 1] -= f * du[i];
        z[i + 1] -= f * z[i];
        dl[i] = 0;
      } else {  // interchange rows i and i + 1
        const double f = d[i] / dl[i];
        d[i] = dl[i];
        const double temp = d[i + 1];
        d[i + 1] = du[i] - f * temp;
        if (i + 2 < static_cast<size_t>(m)) {
          dl[i] = du[i + 1];
          du[i + 1] = -f * dl[i];
        } else {
          dl[i] = 0;
        }
        du[i] = temp;
        std::swap(z[i], z[i + 1]);
        z[i + 1] -= f * z[i];
      }
    }
    const size_t n = static_cast<size_t>(m);
    if (d[n - 1] == 0) d[n - 1] = tiny;
    z[n - 1] /= d[n - 1];
    z[n - 2] = (z[n - 2] - du[n - 2] * z[n - 1]) / d[n - 2];
    for (size_t i = n - 2; i-- > 0;) z[i] = (z[i] - du[i] * z[i + 1] - dl[i] * z[i + 2]) / d[i];
    // Normalise by the largest entry first (the solve can overflow a sum of squares).
    double big = 0;
    for (double v : z) big = std::max(big, std::abs(v));
    if (!(big > 0) || !std::isfinite(big)) return {};
    double norm = 0;
    for (double& v : z) {
      v /= big;
      norm += v * v;
    }
    norm = std::sqrt(norm);
    for (double& v : z) v /= norm;
  }
  return z;
}

}  // namespace dampbound::detail
