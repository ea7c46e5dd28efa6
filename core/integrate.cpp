#include "core/integrate.hpp"

#include <stdexcept>
#include <string>

namespace dampbound {

namespace {

/// Paper eqs. 3-4 (SPEC 2): a = (F - gamma v + f)/m; v += a dt; x += v_new dt.
void semi_implicit_euler(const Model& model, double dt, State& s, const StepWorkspace& ws) {
  for (size_t i = 0; i < s.x.size(); ++i) {
    if (model.fixed[i]) continue;
    const Vec3 a = (ws.force[i] - ws.gamma_eff[i] * s.v[i] + model.external_force[i]) /
                   model.mass[i];
    s.v[i] += a * dt;
    s.x[i] += s.v[i] * dt;
  }
}

/// Forward (explicit) Euler: x += v_old dt; v += a dt.
void forward_euler(const Model& model, double dt, State& s, const StepWorkspace& ws) {
  for (size_t i = 0; i < s.x.size(); ++i) {
    if (model.fixed[i]) continue;
    const Vec3 a = (ws.force[i] - ws.gamma_eff[i] * s.v[i] + model.external_force[i]) /
                   model.mass[i];
    s.x[i] += s.v[i] * dt;
    s.v[i] += a * dt;
  }
}

}  // namespace

int advance(const Model& model, const Params& params, State& state, StepWorkspace& ws) {
  switch (params.integrator) {
    case Integrator::semi_implicit_euler:
      semi_implicit_euler(model, params.dt, state, ws);
      return 0;
    case Integrator::forward_euler:
      forward_euler(model, params.dt, state, ws);
      return 0;
    default:
      break;
  }
  throw std::invalid_argument(std::string("integrator not available: ") +
                              to_string(params.integrator));
}

}  // namespace dampbound
