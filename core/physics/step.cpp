#include "dampbound/physics/step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/physics/detail/spring_pass.hpp"
#include "core/physics/integrate.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/physics/forces.hpp"

namespace dampbound {

namespace {

/// What one chunk of nodes counts in a step; chunks combine exactly (integers, max).
struct ChunkStats {
  int violating = 0, unstabilisable = 0, clamped = 0, unguaranteed = 0;
  double max_displacement = 0;
  bool finite = true;
};

}  // namespace

StepStats step(const Model& model, const Params& params, State& state, StepWorkspace& ws) {
  const size_t n = model.spec().rest.size();
  NodeThreads& threads = ws.pass.threads;
  // A step is a few loops back to back, and steps follow one another: the workers poll for
  // the next loop rather than sleep (docs/performance.md, "step() on threads"). Once per
  // workspace; the Monitor's pool, between whose calls the user's own code runs, sleeps.
  if (threads.spin_microseconds() != kStepSpinMicroseconds)
    threads.set_spin_microseconds(kStepSpinMicroseconds);
  StepStats st;
  // F_i (SPEC 1) and SPEC 9's R_i from the tangent stiffness at t: one pass over the springs.
  const detail::SpringCounts springs =
      detail::spring_pass(model, state.x, &ws.force, &ws.safe_row_sum, &ws.pass);
  st.zero_length_springs = springs.zero_length;
  st.compressed_springs = springs.compressed;
  // SPEC 10: the dashpot and Rayleigh forces from the state at t, like the nodal damping.
  if (model.spring_damping)
    damping_forces(model, state.x, state.v, ws.damping);
  else
    ws.damping.clear();
  const bool damped = !ws.damping.empty();
  // SPEC 10's generalised safe bound where the model has such damping, else SPEC 9's.
  if (damped) damped_safe_gammas(model, state.x, params.dt, ws.safe_bound, &threads);
  ws.upper_bound.resize(n);
  ws.gamma_eff.resize(n);
  ws.status.resize(n);
  ws.safe_bound.resize(n);

  // Bounds and effective damping from the state at t (SPEC 3-4).
  std::vector<ChunkStats> chunk(static_cast<size_t>(threads.chunks(n)));
  threads.run(n, [&](int c, size_t begin, size_t end) {
    ChunkStats cs;  // counted here, stored once: the chunks share cache lines
    for (size_t i = begin; i < end; ++i) {
      if (model.spec().fixed[i]) {
        ws.upper_bound[i] = std::numeric_limits<double>::infinity();
        ws.gamma_eff[i] = 0;
        ws.status[i] = NodeStatus::fixed;
        ws.safe_bound[i] = std::numeric_limits<double>::infinity();
        continue;
      }
      // Eq. 6 with the other damping counted with the spring forces (SPEC 10).
      const double hi =
          damped ? upper_bound(state.v[i], Vec3(ws.force[i] - ws.damping[i]), model.mass[i],
                               params.dt)
                 : upper_bound(state.v[i], ws.force[i], model.mass[i], params.dt);
      const double safe =
          damped ? ws.safe_bound[i] : safe_gamma(model.mass[i], params.dt, ws.safe_row_sum[i]);
      const DampingChoice d = effective_damping(params.policy, model.gamma[i],
                                                model.lower_bound[i], hi, params.factor, safe);
      ws.upper_bound[i] = hi;
      ws.safe_bound[i] = safe;
      ws.gamma_eff[i] = d.gamma;
      ws.status[i] = d.status;
      cs.unguaranteed += d.unguaranteed;
      cs.violating += d.violating;
      cs.unstabilisable += d.unstabilisable;
      cs.clamped += d.status == NodeStatus::clamped;
    }
    chunk[static_cast<size_t>(c)] = cs;
  });
  for (const ChunkStats& cs : chunk) {
    st.unguaranteed += cs.unguaranteed;
    st.violating += cs.violating;
    st.unstabilisable += cs.unstabilisable;
    st.clamped += cs.clamped;
  }
  st.zero_length_springs += advance(model, params, state, ws);
  state.time += params.dt;
  st.iteration = ++state.iteration;
  st.time = state.time;

  // Displacements after the step; a non-finite coordinate makes the step non-finite.
  threads.run(n, [&](int c, size_t begin, size_t end) {
    ChunkStats cs;
    for (size_t i = begin; i < end; ++i) {
      const double d = (state.x[i] - model.spec().rest[i]).norm();
      if (!std::isfinite(d)) {
        cs.finite = false;
        cs.max_displacement = std::numeric_limits<double>::infinity();
      } else if (d > cs.max_displacement) {
        cs.max_displacement = d;
      }
    }
    chunk[static_cast<size_t>(c)] = cs;
  });
  for (const ChunkStats& cs : chunk) {
    st.finite = st.finite && cs.finite;
    st.max_displacement = std::max(st.max_displacement, cs.max_displacement);
  }
  return st;
}

NodeSample sample_node(const Model& model, const State& state, const StepWorkspace& ws, int node) {
  const size_t c = static_cast<size_t>(node);
  NodeSample s;
  const double d = (state.x[c] - model.spec().rest[c]).norm();
  s.displacement = std::isfinite(d) ? d : std::numeric_limits<double>::infinity();
  s.lower = model.lower_bound[c];
  s.upper = ws.upper_bound[c];
  s.gamma = model.gamma[c];
  s.gamma_eff = ws.gamma_eff[c];
  s.safe = ws.safe_bound[c];
  return s;
}

}  // namespace dampbound
