#include "core/protocol.hpp"

namespace dampbound {

const char* to_string(Outcome o) {
  switch (o) {
    case Outcome::running: return "running";
    case Outcome::restored: return "restored";
    case Outcome::diverged: return "diverged";
    case Outcome::not_restored: return "not_restored";
  }
  return "?";
}

Outcome judge(const StopRules& rules, const StepStats& stats) {
  // The comparisons are written so that a NaN falls to diverged, never to restored.
  if (!stats.finite || !(stats.max_displacement <= rules.diverge_factor * rules.reference))
    return Outcome::diverged;
  if (stats.max_displacement < rules.restore_fraction * rules.reference) return Outcome::restored;
  if (stats.iteration >= rules.max_iterations) return Outcome::not_restored;
  return Outcome::running;
}

void accumulate(RunResult& r, const StepStats& st, const StopRules& rules) {
  r.violations += st.violating;
  r.unstabilisable += st.unstabilisable;
  r.clamped += st.clamped;
  r.zero_length_springs += st.zero_length_springs;
  r.unguaranteed += st.unguaranteed;
  r.compressed_springs += st.compressed_springs;
  r.max_displacement = st.max_displacement;
  r.time = st.time;
  if (r.outcome == Outcome::running) {
    r.iterations = st.iteration;
    r.outcome = judge(rules, st);
  }
}

RunResult run_protocol(const Model& model, const Params& params, State& state,
                       const StopRules& rules, int watched, const StepObserver& on_step) {
  StepWorkspace ws;
  RunResult r;
  while (r.outcome == Outcome::running) {
    const StepStats st = step(model, params, state, ws, watched);
    accumulate(r, st, rules);
    if (on_step) on_step(st);
  }
  return r;
}

}  // namespace dampbound
