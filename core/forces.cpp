#include "core/forces.hpp"

namespace dampbound {

int internal_forces(const Model& model, const std::vector<Vec3>& x, std::vector<Vec3>& force) {
  const size_t n = model.rest.size();
  force.resize(n);
  for (size_t i = 0; i < n; ++i)
    force[i] = -model.anchor_kappa[i] * (x[i] - model.rest[i]);
  int zero_length = 0;
  for (size_t k = 0; k < model.springs.size(); ++k) {
    const Spring& s = model.springs[k];
    const size_t i = static_cast<size_t>(s.i), j = static_cast<size_t>(s.j);
    const Vec3 delta = x[j] - x[i];
    const double length = delta.norm();
    if (!(length > 0)) {  // also catches NaN: no direction, no force
      ++zero_length;
      continue;
    }
    const Vec3 f = (model.spring_kappa[k] * (length - s.rest_length) / length) * delta;
    force[i] += f;
    force[j] -= f;
  }
  return zero_length;
}

}  // namespace dampbound
