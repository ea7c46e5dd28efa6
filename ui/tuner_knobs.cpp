#include "ui/tuner_knobs.hpp"

#include <cmath>
#include <utility>

#include "core/analysis/suggest.hpp"

namespace dampbound::ui {

namespace {
/// core's message without the CLI flag it begins with ("--kappa-max: ", "--rayleigh: ").
std::string without_flag(const std::string& message) {
  if (message.rfind("--", 0) != 0) return message;
  const size_t colon = message.find(": ");
  return colon == std::string::npos ? message : message.substr(colon + 2);
}
}  // namespace

void TunerKnobs::start(const Session& session, double zeta, std::uint64_t generation,
                       std::uint64_t topology) {
  if (job_.busy()) return;
  generation_ = generation;
  topology_ = topology;
  params_ = session.params();
  launch(session.shared_scene(), session.shared_model(), session.state().iteration,
         session.params(), session.rules(), zeta, session.springs_cut());
}

void TunerKnobs::start(const SceneSpec& scene, const Params& params, const StopRules& rules,
                       double zeta) {
  if (job_.busy()) return;
  params_ = params;
  generation_ = topology_ = 0;
  launch(std::make_shared<const SceneSpec>(scene), nullptr, 0, params, rules, zeta, 0);
}

void TunerKnobs::launch(std::shared_ptr<const SceneSpec> shared,
                        std::shared_ptr<const Model> model, int iteration, const Params& params,
                        const StopRules& rules, double zeta, int cut) {
  job_.launch([shared = std::move(shared), model = std::move(model), iteration, params, rules,
               zeta, cut, budget = factor_budget_](JobControl& control) {
    std::optional<SceneSpec> as_run;  // the scene as the run has it (its cuts so far)
    if (model) as_run = scene_as_run(*shared, *model, iteration);
    const SceneSpec& scene = as_run ? *as_run : *shared;
    KnobsResult r;
    r.params = params;
    r.springs_cut = cut;
    r.zeta = zeta;
    // Cancel stops the worker before each stage; other errors are the part's own line.
    const auto stage = [&control](const char* what) {
      return [&control, what](const std::string& next) {
        return control.report(std::string(what) + ": " + next);
      };
    };
    try {
      r.ceiling = stiffness_ceiling(scene, params, whole_selection(scene.model), rules, true,
                                    stage("stiffness ceiling"), budget);
    } catch (const SuggestCancelled&) {
      throw;
    } catch (const std::exception& e) {
      r.ceiling_error = without_flag(e.what());
    }
    try {
      RayleighRequest request;
      request.zeta1 = request.zeta2 = zeta;
      r.rayleigh =
          rayleigh_from_spectrum(scene, params, request, stage("Rayleigh pair"), budget);
    } catch (const SuggestCancelled&) {
      throw;
    } catch (const std::exception& e) {
      r.rayleigh_error = without_flag(e.what());
    }
    return r;
  });
}

bool same_model_params(const Params& a, const Params& b) {
  return a.m == b.m && a.kappa == b.kappa && a.gamma == b.gamma && a.dt == b.dt &&
         a.integrator == b.integrator && a.kd == b.kd && a.rayleigh_mass == b.rayleigh_mass &&
         a.rayleigh_stiffness == b.rayleigh_stiffness && a.policy == b.policy &&
         a.factor == b.factor;
}

std::optional<Params> with_kappa_ceiling(const Params& current, const KnobsResult& r) {
  const double f = r.ceiling.factor;
  if (!r.ceiling_error.empty() || !(f > 0) || !std::isfinite(f)) return std::nullopt;
  Params p = current;
  p.kappa = kCeilingMargin * f * r.params.kappa;
  return p;
}

std::optional<Params> with_rayleigh_pair(const Params& current, const KnobsResult& r) {
  if (!r.rayleigh || !r.rayleigh->feasible) return std::nullopt;
  Params p = current;
  p.rayleigh_mass = r.rayleigh->alpha;
  p.rayleigh_stiffness = r.rayleigh->beta;
  return p;
}

}  // namespace dampbound::ui
