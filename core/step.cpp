#include "core/step.hpp"

#include <cmath>
#include <limits>

#include "core/forces.hpp"
#include "core/integrate.hpp"
#include "core/safe_bound.hpp"

namespace dampbound {

StepStats step(const Model& model, const Params& params, State& state, StepWorkspace& ws) {
  const size_t n = model.rest.size();
  StepStats st;
  st.zero_length_springs = internal_forces(model, state.x, ws.force);
  ws.upper_bound.resize(n);
  ws.gamma_eff.resize(n);
  ws.status.resize(n);
  ws.safe_bound.resize(n);
  // SPEC 9: R_i from the tangent stiffness at t, one pass over the springs.
  st.compressed_springs = safe_row_sums(model, state.x, ws.safe_row_sum, &ws.safe_scratch);

  // Bounds and effective damping from the state at t (SPEC 3-4).
  for (size_t i = 0; i < n; ++i) {
    if (model.fixed[i]) {
      ws.upper_bound[i] = std::numeric_limits<double>::infinity();
      ws.gamma_eff[i] = 0;
      ws.status[i] = NodeStatus::fixed;
      ws.safe_bound[i] = std::numeric_limits<double>::infinity();
      continue;
    }
    const double hi = upper_bound(state.v[i], ws.force[i], model.mass[i], params.dt);
    const double safe = safe_gamma(model.mass[i], params.dt, ws.safe_row_sum[i]);
    const DampingChoice c = effective_damping(params.policy, model.gamma[i],
                                              model.lower_bound[i], hi, params.factor, safe);
    ws.upper_bound[i] = hi;
    ws.safe_bound[i] = safe;
    st.unguaranteed += c.unguaranteed;
    ws.gamma_eff[i] = c.gamma;
    ws.status[i] = c.status;
    st.violating += c.violating;
    st.unstabilisable += c.unstabilisable;
    st.clamped += c.status == NodeStatus::clamped;
  }
  st.zero_length_springs += advance(model, params, state, ws);
  state.time += params.dt;
  st.iteration = ++state.iteration;
  st.time = state.time;

  // Displacements after the step; a non-finite coordinate makes the step non-finite.
  double max_d = 0;
  for (size_t i = 0; i < n; ++i) {
    const double d = (state.x[i] - model.rest[i]).norm();
    if (!std::isfinite(d)) {
      st.finite = false;
      max_d = std::numeric_limits<double>::infinity();
    } else if (d > max_d) {
      max_d = d;
    }
  }
  st.max_displacement = max_d;
  return st;
}

NodeSample sample_node(const Model& model, const State& state, const StepWorkspace& ws, int node) {
  const size_t c = static_cast<size_t>(node);
  NodeSample s;
  const double d = (state.x[c] - model.rest[c]).norm();
  s.displacement = std::isfinite(d) ? d : std::numeric_limits<double>::infinity();
  s.lower = model.lower_bound[c];
  s.upper = ws.upper_bound[c];
  s.gamma = model.gamma[c];
  s.gamma_eff = ws.gamma_eff[c];
  s.safe = ws.safe_bound[c];
  return s;
}

}  // namespace dampbound
