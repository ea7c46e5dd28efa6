#include "core/detail/spring_pass.hpp"

#include <algorithm>
#include <cmath>

#include "core/detail/spring_block.hpp"

namespace dampbound::detail {
namespace {

/// One spring at x: its vector and length (what both outputs start from).
struct SpringGeometry {
  Vec3 delta;     ///< x_j - x_i (cm)
  double length;  ///< |delta|; not > 0 (zero or NaN): no direction
};

inline SpringGeometry geometry(const Model& model, const std::vector<Vec3>& x, size_t k) {
  const Spring& s = model.springs[k];
  const Vec3 delta = x[static_cast<size_t>(s.j)] - x[static_cast<size_t>(s.i)];
  return {delta, delta.norm()};
}

/// The force on the spring's first node, kappa_k (l - l0) / l * (x_j - x_i) (SPEC 1).
inline Vec3 spring_force(const Model& model, size_t k, const SpringGeometry& g) {
  return (model.spring_kappa[k] * (g.length - model.springs[k].rest_length) / g.length) * g.delta;
}

/// The spring's tangent block B (upper triangle, b[0..5]) and w = 1/sqrt(m_i m_j) (b[6]);
/// true when compressed (l < l0).
inline bool spring_block(const Model& model, size_t k, const SpringGeometry& g, double* b) {
  const Spring& s = model.springs[k];
  const double l = g.length;
  const double d[3] = {g.delta[0] / l, g.delta[1] / l, g.delta[2] / l};
  const double ratio = s.rest_length / l;
  const double tension = 1.0 - ratio;
  spring_tangent_block(model.spring_kappa[k], tension, ratio, d, b);
  b[6] = 1.0 / std::sqrt(model.mass[static_cast<size_t>(s.i)] * model.mass[static_cast<size_t>(s.j)]);
  return tension < 0;
}

/// |b| summed along row r of a symmetric block, left to right.
inline double row_abs(const double* b, int r) {
  return (std::abs(b[sym3(r, 0)]) + std::abs(b[sym3(r, 1)])) + std::abs(b[sym3(r, 2)]);
}

/// Node i's row-sum accumulators: K_ii's upper triangle (6), then the off-diagonal row sums
/// of |A| (3); the anchor adds kappa_a I to K_ii (SPEC 7).
inline void start_rows(const Model& model, size_t i, double* a) {
  const double ka = model.anchor_kappa[i];
  for (int q = 0; q < 9; ++q) a[q] = 0;
  a[0] = a[3] = a[5] = ka;  // element by element: copying a block in stalls store forwarding
}

/// After spring block b: K_ii += B (K_ij = -B), and A_rs = K_rs / sqrt(m_r m_s) adds |B| w
/// to the row sums unless the other node is fixed.
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

inline Vec3 anchor_force(const Model& model, const std::vector<Vec3>& x, size_t i) {
  return -model.anchor_kappa[i] * (x[i] - model.rest[i]);
}

}  // namespace

SpringCounts spring_pass(const Model& model, const std::vector<Vec3>& x,
                         std::vector<Vec3>* force, std::vector<double>* row_sum,
                         SpringPass* pass) {
  const std::vector<std::uint8_t>& fixed = model.fixed;
  const size_t n = x.size(), ns = model.springs.size();
  if (force) force->resize(n);
  if (row_sum) row_sum->assign(n, 0.0);
  SpringCounts counts;
  if (!pass || pass->threads.chunks(ns) <= 1) {
    // One thread: the anchor terms, then one loop over the springs adding each spring's terms
    // to both of its nodes (+f to i, -f to j; B to each free end).
    std::vector<double> acc(row_sum ? 9 * n : 0);
    for (size_t i = 0; i < n; ++i) {
      if (force) (*force)[i] = anchor_force(model, x, i);
      if (row_sum) start_rows(model, i, &acc[9 * i]);
    }
    double b[7];
    for (size_t k = 0; k < ns; ++k) {
      const SpringGeometry g = geometry(model, x, k);
      if (!(g.length > 0)) {  // also catches NaN
        ++counts.zero_length;
        continue;
      }
      const size_t i = static_cast<size_t>(model.springs[k].i);
      const size_t j = static_cast<size_t>(model.springs[k].j);
      if (force) {
        const Vec3 f = spring_force(model, k, g);
        (*force)[i] += f;
        (*force)[j] -= f;
      }
      if (row_sum) {
        counts.compressed += spring_block(model, k, g, b);
        if (!fixed[i]) add_block(&acc[9 * i], b, fixed[j]);
        if (!fixed[j]) add_block(&acc[9 * j], b, fixed[i]);
      }
    }
    if (row_sum)
      for (size_t i = 0; i < n; ++i)
        if (!fixed[i]) (*row_sum)[i] = row_sum_of(&acc[9 * i], model.mass[i]);
    return counts;
  }
  // Threads. Pass 1: every spring once, its force (3 doubles) and its block (7, in a second
  // array after the forces). Pass 2: per node, the anchor term, then its springs in index
  // order: the additions of the loop above in the same order, so the same bits.
  SpringPass& p = *pass;
  const size_t blocks_at = force ? 3 * ns : 0;
  p.values.resize(blocks_at + (row_sum ? 7 * ns : 0));
  p.skip.resize(ns);
  const size_t chunks = static_cast<size_t>(p.threads.chunks(ns));
  p.counts.assign(2 * chunks, 0);
  p.threads.run(ns, [&](int chunk, size_t begin, size_t end) {
    int zero = 0, compressed = 0;
    for (size_t k = begin; k < end; ++k) {
      const Spring& s = model.springs[k];
      const SpringGeometry g = geometry(model, x, k);
      const bool skip = !(g.length > 0);
      // Bit 0: no direction; bits 1 and 2: node i, node j fixed (what pass 2 would otherwise
      // look up through the spring).
      p.skip[k] = static_cast<std::uint8_t>((skip ? 1 : 0) | fixed[static_cast<size_t>(s.i)] << 1 |
                                            fixed[static_cast<size_t>(s.j)] << 2);
      if (skip) {
        ++zero;
        continue;
      }
      if (force) Eigen::Map<Vec3>{&p.values[3 * k]} = spring_force(model, k, g);
      if (row_sum) compressed += spring_block(model, k, g, &p.values[blocks_at + 7 * k]);
    }
    p.counts[2 * static_cast<size_t>(chunk)] = zero;
    p.counts[2 * static_cast<size_t>(chunk) + 1] = compressed;
  });
  p.threads.run(n, [&](int, size_t begin, size_t end) {
    double a[9];
    for (size_t i = begin; i < end; ++i) {
      const bool rows = row_sum && !fixed[i];
      if (!force && !rows) continue;  // a fixed node has no rows
      // The force as three scalars, not a Vec3: a vector kept in memory across the loop
      // stalls on store forwarding (a third of this loop's time at 40k nodes).
      double f0 = 0, f1 = 0, f2 = 0;
      if (force) {
        const Vec3 anchor = anchor_force(model, x, i);
        f0 = anchor[0];
        f1 = anchor[1];
        f2 = anchor[2];
      }
      if (rows) start_rows(model, i, a);
      for (int e = model.incident_offset[i]; e < model.incident_offset[i + 1]; ++e) {
        const int k = model.incident[static_cast<size_t>(e)];
        const size_t spring = static_cast<size_t>(k >= 0 ? k : ~k);
        const std::uint8_t flags = p.skip[spring];
        if (flags & 1) continue;
        if (force) {
          const double* f = &p.values[3 * spring];
          if (k >= 0) {
            f0 = f0 + f[0];
            f1 = f1 + f[1];
            f2 = f2 + f[2];
          } else {
            f0 = f0 - f[0];
            f1 = f1 - f[1];
            f2 = f2 - f[2];
          }
        }
        if (rows) add_block(a, &p.values[blocks_at + 7 * spring], (flags & (k >= 0 ? 4 : 2)) != 0);
      }
      if (force) (*force)[i] = Vec3(f0, f1, f2);
      if (rows) (*row_sum)[i] = row_sum_of(a, model.mass[i]);
    }
  });
  for (size_t c = 0; c < chunks; ++c) {
    counts.zero_length += p.counts[2 * c];
    counts.compressed += p.counts[2 * c + 1];
  }
  return counts;
}

}  // namespace dampbound::detail
