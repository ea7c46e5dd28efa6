#include "core/physics/safe_bound_nodes.hpp"

#include "core/physics/safe_bound.hpp"

namespace dampbound {

void safe_bounds_per_node(const Model& model, const std::vector<Vec3>& x, double dt,
                          std::vector<double>& dt_safe, std::vector<double>& gamma_safe) {
  const size_t n = model.mass.size();
  dt_safe.assign(n, 0);
  gamma_safe.assign(n, 0);
  const NodeSafeBounds rows(model, x);
  for (size_t i = 0; i < n; ++i) {
    if (model.spec().fixed[i]) continue;
    dt_safe[i] = rows.dt_safe(static_cast<int>(i), model.gamma[i]);
    gamma_safe[i] = rows.gamma_safe(static_cast<int>(i), dt);
  }
}

}  // namespace dampbound
