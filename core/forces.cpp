#include "core/forces.hpp"

namespace dampbound {

namespace {

/// Spring k's force on its first node at positions x, kappa_k (l - l0) / l * (x_j - x_i);
/// false when the spring has no direction (zero or NaN length): no force.
inline bool spring_force(const Model& model, const std::vector<Vec3>& x, size_t k, Vec3& f) {
  const Spring& s = model.springs[k];
  const Vec3 delta = x[static_cast<size_t>(s.j)] - x[static_cast<size_t>(s.i)];
  const double length = delta.norm();
  if (!(length > 0)) return false;  // also catches NaN
  f = (model.spring_kappa[k] * (length - s.rest_length) / length) * delta;
  return true;
}

}  // namespace

int internal_forces(const Model& model, const std::vector<Vec3>& x, std::vector<Vec3>& force,
                    SpringPass* pass) {
  const size_t n = model.rest.size(), ns = model.springs.size();
  force.resize(n);
  int zero_length = 0;
  if (!pass || pass->threads.chunks(ns) <= 1) {
    // One thread: the anchor terms, then one loop over the springs adding +f to i, -f to j.
    for (size_t i = 0; i < n; ++i) force[i] = -model.anchor_kappa[i] * (x[i] - model.rest[i]);
    Vec3 f = Vec3::Zero();
    for (size_t k = 0; k < ns; ++k) {
      if (!spring_force(model, x, k, f)) {
        ++zero_length;
        continue;
      }
      force[static_cast<size_t>(model.springs[k].i)] += f;
      force[static_cast<size_t>(model.springs[k].j)] -= f;
    }
    return zero_length;
  }
  // Threads. Pass 1: every spring's force once. Pass 2: per node, the anchor term, then its
  // springs in index order (+f where it is the first node, -f where the second): the very
  // additions of the loop above, in the same order, so the same bits.
  SpringPass& p = *pass;
  p.values.resize(3 * ns);
  p.skip.resize(ns);
  p.counts.assign(static_cast<size_t>(p.threads.chunks(ns)), 0);
  p.threads.run(ns, [&](int chunk, size_t begin, size_t end) {
    int zero = 0;
    Vec3 f = Vec3::Zero();
    for (size_t k = begin; k < end; ++k) {
      p.skip[k] = !spring_force(model, x, k, f);
      if (p.skip[k]) {
        ++zero;
        continue;
      }
      Eigen::Map<Vec3>(&p.values[3 * k]) = f;
    }
    p.counts[static_cast<size_t>(chunk)] = zero;
  });
  p.threads.run(n, [&](int, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      Vec3 sum = -model.anchor_kappa[i] * (x[i] - model.rest[i]);
      for (int e = model.incident_offset[i]; e < model.incident_offset[i + 1]; ++e) {
        const int k = model.incident[static_cast<size_t>(e)];
        const size_t spring = static_cast<size_t>(k >= 0 ? k : ~k);
        if (p.skip[spring]) continue;
        const Eigen::Map<const Vec3> f(&p.values[3 * spring]);
        if (k >= 0)
          sum += f;
        else
          sum -= f;
      }
      force[i] = sum;
    }
  });
  for (int c : p.counts) zero_length += c;
  return zero_length;
}

}  // namespace dampbound
