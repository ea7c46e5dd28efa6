#include "core/forces.hpp"

namespace dampbound {

int internal_forces(const Model& model, const std::vector<Vec3>& x, std::vector<Vec3>& force,
                    SpringPass* pass) {
  SpringPass local;
  SpringPass& p = pass ? *pass : local;
  const size_t n = model.rest.size(), ns = model.springs.size();
  force.resize(n);
  p.values.resize(3 * ns);
  p.skip.resize(ns);
  p.counts.assign(static_cast<size_t>(p.threads.chunks(ns)), 0);
  // Pass 1: f_k = kappa_k (l - l0) / l * (x_j - x_i), or skip where it has no direction.
  p.threads.run(ns, [&](int chunk, size_t begin, size_t end) {
    int zero_length = 0;
    for (size_t k = begin; k < end; ++k) {
      const Spring& s = model.springs[k];
      const Vec3 delta = x[static_cast<size_t>(s.j)] - x[static_cast<size_t>(s.i)];
      const double length = delta.norm();
      p.skip[k] = !(length > 0);  // also catches NaN: no direction, no force
      if (p.skip[k]) {
        ++zero_length;
        continue;
      }
      Eigen::Map<Vec3>(&p.values[3 * k]) = (model.spring_kappa[k] * (length - s.rest_length) / length) * delta;
    }
    p.counts[static_cast<size_t>(chunk)] = zero_length;
  });
  // Pass 2: the anchor term, then +f_k where i is the spring's first node, -f_k where second.
  p.threads.run(n, [&](int, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      Vec3 sum = -model.anchor_kappa[i] * (x[i] - model.rest[i]);
      for (int e = model.incident_offset[i]; e < model.incident_offset[i + 1]; ++e) {
        const int k = model.incident[static_cast<size_t>(e)];
        const size_t spring = static_cast<size_t>(k >= 0 ? k : ~k);
        if (p.skip[spring]) continue;
        const double* f = &p.values[3 * spring];
        if (k >= 0)
          sum += Eigen::Map<const Vec3>(f);
        else
          sum -= Eigen::Map<const Vec3>(f);
      }
      force[i] = sum;
    }
  });
  int zero_length = 0;
  for (int c : p.counts) zero_length += c;
  return zero_length;
}

}  // namespace dampbound
