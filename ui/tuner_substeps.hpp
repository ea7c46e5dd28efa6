#pragma once
// The Suggest tab's substeps per frame (core/analysis/substeps.hpp) on a worker thread: for a
// frame time F the fewest n with dt = F/n stable by the exact limit and the n the safe bound
// (SPEC 9) guarantees, each run from the mesh as it is now (and, where the exact count
// diverges, the fewest count that holds, found by running), with progress and Cancel as
// Suggest has. Where one step per frame is not stable, also SPEC 11's alternative: the least
// mass to add so that dt = F is (core/analysis/mass_scaling_scene.hpp), with its run.
#include <memory>
#include <optional>
#include <string>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/mass_scaling_scene.hpp"
#include "core/analysis/substeps.hpp"
#include "dampbound/run/session.hpp"
#include "ui/background_job.hpp"

namespace dampbound::ui {

/// The substeps of one frame time, and for which parameters and mesh.
struct SubstepsResult {
  Params params;                ///< the parameters asked for (dt aside)
  SubstepSuggestion substeps;   ///< both counts and their verifying runs
  int springs_cut = 0;          ///< springs cut away before (by hand or by the scene)
  /// SPEC 11 at dt* = F (one step per frame), where the exact count is not 1: the answer,
  /// its run and the scene with the scaled masses (what "apply mass" switches to).
  std::optional<SceneMassScaling> mass;
  std::string mass_error;  ///< why there is no `mass` where one was asked (over the budget)
};

/// Per node, the added mass of `m` over the largest (0..1; empty when none was added): what
/// the mesh view colours by.
std::vector<float> added_mass_shade(const SceneMassScaling& m);

/// The default frame time: 1/60 s.
inline constexpr double kDefaultFrameDt = 1.0 / 60.0;

class TunerSubsteps {
 public:
  /// Starts the computation for the mesh the session has now (its cuts count), its
  /// parameters and rules, and the frame time `frame_dt` (s, > 0); ignored while one runs.
  void start(const Session& session, double frame_dt);
  /// The same for a scene as given.
  void start(const SceneSpec& scene, const Params& params, const StopRules& rules,
             double frame_dt);
  BackgroundJob<SubstepsResult>& job() { return job_; }
  const BackgroundJob<SubstepsResult>& job() const { return job_; }
  /// The most one factorisation of the next start() may cost (flops; --factor-budget):
  /// over it the count comes from what is proved without one and mass scaling says so.
  void set_factor_budget(double flops) { factor_budget_ = flops; }

 private:
  void launch(std::shared_ptr<const SceneSpec> scene, std::shared_ptr<const Model> model,
              int iteration, const Params& params, const StopRules& rules, double frame_dt,
              int cut);
  BackgroundJob<SubstepsResult> job_;
  double factor_budget_ = kDefaultFactorBudget;
};

/// `current` with dt = F/n of one count (unchanged when the count has none).
Params with_substeps(const Params& current, const SubstepCount& count);

}  // namespace dampbound::ui
