#include "core/safe_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/analysis/linear_stability.hpp"
#include "core/forces.hpp"
#include "core/detail/spring_block.hpp"

namespace dampbound {

int safe_row_sums(const Model& model, const std::vector<Vec3>& x, std::vector<double>& row_sum,
                  SpringPass* pass) {
  SpringPass local;
  SpringPass& p = pass ? *pass : local;
  const std::vector<double>& mass = model.mass;
  const std::vector<std::uint8_t>& fixed = model.fixed;
  const size_t n = x.size(), ns = model.springs.size();
  // |b| summed along row r of a symmetric block, left to right.
  auto row_abs = [](const double* b, int r) {
    return (std::abs(b[sym3(r, 0)]) + std::abs(b[sym3(r, 1)])) + std::abs(b[sym3(r, 2)]);
  };
  // Pass 1, per spring: its tangent block B (upper triangle, 6) and w = 1/sqrt(m_i m_j).
  constexpr size_t kStride = 7;
  p.values.resize(kStride * ns);
  p.skip.resize(ns);
  p.counts.assign(static_cast<size_t>(p.threads.chunks(ns)), 0);
  p.threads.run(ns, [&](int chunk, size_t begin, size_t end) {
    int compressed = 0;
    for (size_t k = begin; k < end; ++k) {
      const Spring& s = model.springs[k];
      const size_t i = static_cast<size_t>(s.i), j = static_cast<size_t>(s.j);
      const Vec3 delta = x[j] - x[i];
      const double l = delta.norm();
      p.skip[k] = !(l > 0);  // no direction: no force, no stiffness (SPEC 1)
      if (p.skip[k]) continue;
      const double d[3] = {delta[0] / l, delta[1] / l, delta[2] / l};
      const double ratio = s.rest_length / l;
      const double tension = 1.0 - ratio;
      compressed += tension < 0;
      double* b = &p.values[kStride * k];
      spring_tangent_block(model.spring_kappa[k], tension, ratio, d, b);
      b[6] = 1.0 / std::sqrt(mass[i] * mass[j]);
    }
    p.counts[static_cast<size_t>(chunk)] = compressed;
  });
  // Pass 2, per free node, its springs in index order: K_ii += B (the anchor adds kappa_a I,
  // SPEC 7), and the row sums of |A| over the off-diagonal blocks, A_rs = K_rs / sqrt(m_r
  // m_s) with K_ij = -B; columns of fixed nodes drop out.
  row_sum.assign(n, 0.0);
  p.threads.run(n, [&](int, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (fixed[i]) continue;
      const double ka = model.anchor_kappa[i];
      double a[9] = {ka, 0, 0, ka, 0, ka, 0, 0, 0};
      for (int e = model.incident_offset[i]; e < model.incident_offset[i + 1]; ++e) {
        const int k = model.incident[static_cast<size_t>(e)];
        const size_t spring = static_cast<size_t>(k >= 0 ? k : ~k);
        if (p.skip[spring]) continue;
        const Spring& s = model.springs[spring];
        const double* b = &p.values[kStride * spring];
        for (int q = 0; q < 6; ++q) a[q] = a[q] + b[q];
        if (!fixed[static_cast<size_t>(k >= 0 ? s.j : s.i)])
          for (int r = 0; r < 3; ++r) a[6 + r] = a[6 + r] + row_abs(b, r) * b[6];
      }
      const double r0 = row_abs(a, 0) / mass[i] + a[6];
      const double r1 = row_abs(a, 1) / mass[i] + a[7];
      const double r2 = row_abs(a, 2) / mass[i] + a[8];
      row_sum[i] = std::max(std::max(r0, r1), r2);
    }
  });
  int compressed = 0;
  for (int c : p.counts) compressed += c;
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
