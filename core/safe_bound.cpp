#include "core/safe_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/analysis/linear_stability.hpp"
#include "core/forces.hpp"
#include "core/detail/spring_block.hpp"

namespace dampbound {

namespace {

/// Spring k's tangent block B at x (upper triangle, b[0..5]) and w = 1/sqrt(m_i m_j) (b[6]);
/// false when it has no direction (no force, no stiffness, SPEC 1). `compressed` when l < l0.
inline bool spring_block(const Model& model, const std::vector<Vec3>& x, size_t k, double* b,
                         bool& compressed) {
  const Spring& s = model.springs[k];
  const size_t i = static_cast<size_t>(s.i), j = static_cast<size_t>(s.j);
  const Vec3 delta = x[j] - x[i];
  const double l = delta.norm();
  if (!(l > 0)) return false;
  const double d[3] = {delta[0] / l, delta[1] / l, delta[2] / l};
  const double ratio = s.rest_length / l;
  const double tension = 1.0 - ratio;
  compressed = tension < 0;
  spring_tangent_block(model.spring_kappa[k], tension, ratio, d, b);
  b[6] = 1.0 / std::sqrt(model.mass[i] * model.mass[j]);
  return true;
}

/// |b| summed along row r of a symmetric block, left to right.
inline double row_abs(const double* b, int r) {
  return (std::abs(b[sym3(r, 0)]) + std::abs(b[sym3(r, 1)])) + std::abs(b[sym3(r, 2)]);
}

/// Node i's accumulators (K_ii's upper triangle, then the off-diagonal row sums) after spring
/// block b where `other` is the spring's other node: K_ii += B (K_ij = -B), and A_rs =
/// K_rs / sqrt(m_r m_s) adds |B| w to the row sums unless the other node is fixed.
inline void add_block(double* a, const double* b, bool other_fixed) {
  for (int q = 0; q < 6; ++q) a[q] = a[q] + b[q];
  if (!other_fixed)
    for (int r = 0; r < 3; ++r) a[6 + r] = a[6 + r] + row_abs(b, r) * b[6];
}

/// R_i = the largest of node i's three row sums: the diagonal block's |.| / m_i plus the rest.
inline double row_sum_of(const double* a, double mass) {
  const double r0 = row_abs(a, 0) / mass + a[6];
  const double r1 = row_abs(a, 1) / mass + a[7];
  const double r2 = row_abs(a, 2) / mass + a[8];
  return std::max(std::max(r0, r1), r2);
}

}  // namespace

int safe_row_sums(const Model& model, const std::vector<Vec3>& x, std::vector<double>& row_sum,
                  SpringPass* pass) {
  const std::vector<std::uint8_t>& fixed = model.fixed;
  const size_t n = x.size(), ns = model.springs.size();
  row_sum.assign(n, 0.0);
  // Per node: the diagonal block K_ii (upper triangle, 6) and the row sums of |A| over the
  // off-diagonal blocks (3). The anchor adds kappa_a I to K_ii (SPEC 7).
  auto start = [&](size_t i, double* a) {
    const double ka = model.anchor_kappa[i];
    const double init[9] = {ka, 0, 0, ka, 0, ka, 0, 0, 0};
    std::copy(init, init + 9, a);
  };
  if (!pass || pass->threads.chunks(ns) <= 1) {
    // One thread: one loop over the springs adding each block to both of its free nodes.
    std::vector<double> acc(9 * n);
    for (size_t i = 0; i < n; ++i) start(i, &acc[9 * i]);
    int compressed = 0;
    double b[7];
    for (size_t k = 0; k < ns; ++k) {
      bool c = false;
      if (!spring_block(model, x, k, b, c)) continue;
      compressed += c;
      const size_t i = static_cast<size_t>(model.springs[k].i);
      const size_t j = static_cast<size_t>(model.springs[k].j);
      if (!fixed[i]) add_block(&acc[9 * i], b, fixed[j]);
      if (!fixed[j]) add_block(&acc[9 * j], b, fixed[i]);
    }
    for (size_t i = 0; i < n; ++i)
      if (!fixed[i]) row_sum[i] = row_sum_of(&acc[9 * i], model.mass[i]);
    return compressed;
  }
  // Threads. Pass 1: every spring's block once. Pass 2: per free node, its springs in index
  // order: the additions of the loop above in the same order, so the same bits.
  SpringPass& p = *pass;
  constexpr size_t kStride = 7;
  p.values.resize(kStride * ns);
  p.skip.resize(ns);
  p.counts.assign(static_cast<size_t>(p.threads.chunks(ns)), 0);
  p.threads.run(ns, [&](int chunk, size_t begin, size_t end) {
    int compressed = 0;
    for (size_t k = begin; k < end; ++k) {
      bool c = false;
      const Spring& s = model.springs[k];
      // Bit 0: no direction; bits 1 and 2: node i, node j fixed (what pass 2 would otherwise
      // look up through the spring).
      const bool skip = !spring_block(model, x, k, &p.values[kStride * k], c);
      p.skip[k] = static_cast<std::uint8_t>((skip ? 1 : 0) | fixed[static_cast<size_t>(s.i)] << 1 |
                                            fixed[static_cast<size_t>(s.j)] << 2);
      compressed += c;
    }
    p.counts[static_cast<size_t>(chunk)] = compressed;
  });
  p.threads.run(n, [&](int, size_t begin, size_t end) {
    double a[9];
    for (size_t i = begin; i < end; ++i) {
      if (fixed[i]) continue;
      start(i, a);
      for (int e = model.incident_offset[i]; e < model.incident_offset[i + 1]; ++e) {
        const int k = model.incident[static_cast<size_t>(e)];
        const size_t spring = static_cast<size_t>(k >= 0 ? k : ~k);
        const std::uint8_t flags = p.skip[spring];
        if (flags & 1) continue;
        add_block(a, &p.values[kStride * spring], (flags & (k >= 0 ? 4 : 2)) != 0);  // other end
      }
      row_sum[i] = row_sum_of(a, model.mass[i]);
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
