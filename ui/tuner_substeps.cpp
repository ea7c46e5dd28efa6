#include "ui/tuner_substeps.hpp"

#include <utility>

#include "core/analysis/suggest.hpp"

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
               frame_dt, cut](JobControl& control) {
    std::optional<SceneSpec> as_run;  // the scene as the run has it (its cuts so far)
    if (model) as_run = scene_as_run(*shared, *model, iteration);
    const SceneSpec& scene = as_run ? *as_run : *shared;
    SubstepsResult r;
    r.params = params;
    r.springs_cut = cut;
    SuggestOptions options;  // Cancel stops the worker before the analysis and each run
    options.progress = [&control](int, int, const std::string& next) {
      return control.report("substeps: " + next);
    };
    r.substeps = suggest_substeps(scene, params, rules, frame_dt, options);
    return r;
  });
}

Params with_substeps(const Params& current, const SubstepCount& count) {
  Params p = current;
  if (count.n > 0 && count.dt > 0) p.dt = count.dt;
  return p;
}

}  // namespace dampbound::ui
