#include "core/safe_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/analysis/linear_stability.hpp"
#include "core/detail/spring_block.hpp"

namespace dampbound {

int safe_row_sums(const Model& model, const std::vector<Vec3>& x, std::vector<double>& row_sum,
                  std::vector<double>* scratch) {
  const std::vector<double>& mass = model.mass;
  const std::vector<double>& anchor_kappa = model.anchor_kappa;
  const std::vector<std::uint8_t>& fixed = model.fixed;
  const size_t n = x.size();
  std::vector<double> local;
  std::vector<double>& acc = scratch ? *scratch : local;
  // Per node: the diagonal block K_ii (upper triangle, 6) and the row sums of |A| over the
  // off-diagonal blocks (3). The anchor adds kappa_a I to K_ii (SPEC 7).
  acc.assign(9 * n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    double* a = &acc[9 * i];
    a[0] = a[3] = a[5] = anchor_kappa[i];
  }
  // |b| summed along row r of a symmetric block, left to right.
  auto row_abs = [](const double* b, int r) {
    return (std::abs(b[sym3(r, 0)]) + std::abs(b[sym3(r, 1)])) + std::abs(b[sym3(r, 2)]);
  };
  int compressed = 0;
  for (size_t k = 0; k < model.springs.size(); ++k) {
    const Spring& s = model.springs[k];
    const size_t i = static_cast<size_t>(s.i), j = static_cast<size_t>(s.j);
    const Vec3 delta = x[j] - x[i];
    const double l = delta.norm();
    if (!(l > 0)) continue;  // no direction: no force, no stiffness (SPEC 1)
    const double d[3] = {delta[0] / l, delta[1] / l, delta[2] / l};
    const double ratio = s.rest_length / l;
    const double tension = 1.0 - ratio;
    compressed += tension < 0;
    double b[6];
    spring_tangent_block(model.spring_kappa[k], tension, ratio, d, b);
    // K_ii += B, K_jj += B, K_ij = K_ji = -B; A_rs = K_rs / sqrt(m_r m_s).
    const double w = 1.0 / std::sqrt(mass[i] * mass[j]);
    for (size_t node : {i, j}) {
      if (fixed[node]) continue;
      double* a = &acc[9 * node];
      for (int k = 0; k < 6; ++k) a[k] = a[k] + b[k];
      if (!fixed[node == i ? j : i])
        for (int r = 0; r < 3; ++r) a[6 + r] = a[6 + r] + row_abs(b, r) * w;
    }
  }
  row_sum.assign(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    if (fixed[i]) continue;
    const double* a = &acc[9 * i];
    const double r0 = row_abs(a, 0) / mass[i] + a[6];
    const double r1 = row_abs(a, 1) / mass[i] + a[7];
    const double r2 = row_abs(a, 2) / mass[i] + a[8];
    row_sum[i] = std::max(std::max(r0, r1), r2);
  }
  return compressed;
}

double safe_dt(double m, double gamma, double row_sum) {
  // The positive root of R dt^2 + 2 c dt = 4: SPEC 7's formula with lambda_max -> R_i.
  return semi_implicit_dt_max(row_sum, gamma / m);
}

SafeBoundSummary safe_bound_summary(const Model& model, const std::vector<Vec3>& x, double dt) {
  SafeBoundSummary s;
  std::vector<double> R;
  s.compressed_springs = safe_row_sums(model, x, R);
  s.gamma_safe = s.dt_safe = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < R.size(); ++i) {
    if (model.fixed[i]) continue;
    ++s.free_nodes;
    const int node = static_cast<int>(i);
    const double g = safe_gamma(model.mass[i], dt, R[i]);
    if (g < s.gamma_safe) {
      s.gamma_safe = g;
      s.gamma_node = node;
      s.row_sum = R[i];
    }
    const double h = safe_dt(model.mass[i], model.gamma[i], R[i]);
    if (h < s.dt_safe) {
      s.dt_safe = h;
      s.dt_node = node;
    }
    if (model.lower_bound[i] > g) {
      s.infeasible.push_back(node);
      s.infeasible_dt.push_back(safe_dt(model.mass[i], model.lower_bound[i], R[i]));
    }
  }
  return s;
}

}  // namespace dampbound
