#include "ui/tuner_substeps.hpp"

#include <string>
#include <utility>

#include <algorithm>

#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/suggest.hpp"
#include "core/physics/integrate.hpp"

namespace dampbound::ui {

void TunerSubsteps::start(const Session& session, double frame_dt) {
  launch(session.shared_scene(), session.shared_model(), session.state().iteration,
         session.params(), session.rules(), frame_dt, session.springs_cut());
}

void TunerSubsteps::start(const SceneSpec& scene, const Params& params, const StopRules& rules,
                          double frame_dt) {
  launch(std::make_shared<const SceneSpec>(scene), nullptr, 0, params, rules, frame_dt, 0);
}

void TunerSubsteps::launch(std::shared_ptr<const SceneSpec> shared,
                           std::shared_ptr<const Model> model, int iteration,
                           const Params& params, const StopRules& rules, double frame_dt,
                           int cut) {
  job_.launch([shared = std::move(shared), model = std::move(model), iteration, params, rules,
               frame_dt, cut, budget = factor_budget_](JobControl& control) {
    std::optional<SceneSpec> as_run;  // the scene as the run has it (its cuts so far)
    if (model) as_run = scene_as_run(*shared, *model, iteration);
    const SceneSpec& scene = as_run ? *as_run : *shared;
    SubstepsResult r;
    r.params = params;
    r.springs_cut = cut;
    SuggestOptions options;  // Cancel stops the worker before the analysis and each run
    options.max_factor_flops = budget;
    options.progress = [&control](int, int, const std::string& next) {
      return control.report("substeps: " + next);
    };
    r.substeps = suggest_substeps(scene, params, rules, frame_dt, options);
    if (r.substeps.exact.n != 1 && integrator_traits(params.integrator).paper_step) {
      SceneMassScalingOptions o;
      o.max_factor_flops = budget;
      o.progress = [&control](const std::string& next) {
        return control.report("mass scaling: " + next);
      };
      try {
        r.mass = scene_mass_scaling(scene, params, rules, frame_dt, o);
      } catch (const FactorisationOverBudget& over) {
        r.mass_error = std::string("mass scaling not computed: ") + over.what();
      }
    }
    return r;
  });
}

std::vector<float> added_mass_shade(const SceneMassScaling& m) {
  double top = 0;
  for (size_t i = 0; i < m.mass_after.size(); ++i)
    top = std::max(top, m.mass_after[i] - m.mass_before[i]);
  std::vector<float> shade;
  if (!(top > 0)) return shade;
  for (size_t i = 0; i < m.mass_after.size(); ++i)
    shade.push_back(static_cast<float>((m.mass_after[i] - m.mass_before[i]) / top));
  return shade;
}

Params with_substeps(const Params& current, const SubstepCount& count) {
  Params p = current;
  if (count.n > 0 && count.dt > 0) p.dt = count.dt;
  return p;
}

}  // namespace dampbound::ui
