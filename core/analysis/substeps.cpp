#include "core/analysis/substeps.hpp"

#include <cmath>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/safe_bound.hpp"

namespace dampbound {

int substeps_below(double frame_dt, double limit) {
  if (!(limit > 0) || !(frame_dt > 0)) return 0;
  if (std::isinf(limit)) return 1;
  const double q = std::floor(frame_dt / limit);
  if (q >= kMaxSubsteps) return 0;
  int n = static_cast<int>(q) + 1;
  // frame_dt / limit rounds: step to the exact fewest n in the doubles the run will use.
  while (n > 1 && frame_dt / (n - 1) < limit) --n;
  while (!(frame_dt / n < limit) && n < kMaxSubsteps) ++n;
  return frame_dt / n < limit ? n : 0;
}

SubstepSuggestion suggest_substeps(const SceneSpec& scene, const Params& params,
                                   const StopRules& rules, double frame_dt, bool verify) {
  SubstepSuggestion s;
  s.frame_dt = frame_dt;
  Params p = params;
  p.dt = frame_dt;
  const Model model = compile_model(scene.model, p);
  const State rest = rest_state(model);
  const ExactStability exact = exact_stability(model, rest.x, p);
  s.exact.limit = exact.computed() ? exact.dt_max : 0;
  if (!exact.computed()) s.note = "exact limit not computed: " + exact.over_budget_reason();
  s.safe.limit = safe_bound_summary(model, rest.x, p.dt).dt_safe;
  for (SubstepCount* c : {&s.exact, &s.safe}) {
    c->n = substeps_below(frame_dt, c->limit);
    if (c->n == 0) continue;
    c->dt = frame_dt / c->n;
    if (!verify) continue;
    Params at = p;
    at.dt = c->dt;
    c->run = verify_run(scene, at, rules,
                        std::to_string(c->n) + " substeps (" +
                            (c == &s.exact ? "exact limit" : "safe bound") + ")");
    c->ran = true;
  }
  return s;
}

}  // namespace dampbound
