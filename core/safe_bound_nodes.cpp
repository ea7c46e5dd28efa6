#include "core/safe_bound_nodes.hpp"

#include "core/safe_bound.hpp"

namespace dampbound {

void safe_bounds_per_node(const Model& model, const std::vector<Vec3>& x, double dt,
                          std::vector<double>& dt_safe, std::vector<double>& gamma_safe) {
  const size_t n = model.mass.size();
  dt_safe.assign(n, 0);
  gamma_safe.assign(n, 0);
  if (model.spring_damping) {  // SPEC 10: the generalised rows, the other damping held
    const DampedSafeRows rows(model, x);
    for (size_t i = 0; i < n; ++i) {
      if (model.spec().fixed[i]) continue;
      dt_safe[i] = rows.dt_safe(static_cast<int>(i), model.gamma[i]);
      gamma_safe[i] = rows.gamma_safe(static_cast<int>(i), dt);
    }
    return;
  }
  std::vector<double> row_sum;
  safe_row_sums(model, x, row_sum);
  for (size_t i = 0; i < n; ++i) {
    if (model.spec().fixed[i]) continue;
    dt_safe[i] = safe_dt(model.mass[i], model.gamma[i], row_sum[i]);
    gamma_safe[i] = safe_gamma(model.mass[i], dt, row_sum[i]);
  }
}

}  // namespace dampbound
