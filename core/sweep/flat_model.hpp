#pragma once
// The trial body's inputs (core/sweep/detail/trial_body.hpp) from a scene, and its host copy:
// what the GPU sweep copies to the device, and what the tests run on the CPU to compare the
// body bit for bit with the batched kernel and step().
#include <optional>
#include <string>
#include <vector>

#include "core/sweep/detail/trial_data.hpp"
#include "core/sweep/kernel.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// Why the trial body cannot run a scene (nullopt when it can): cuts (topology changes
/// mid-run) and integrators other than the paper's semi-implicit Euler and forward Euler.
/// Unlike the batched kernel, it runs SPEC 10's dashpot and Rayleigh damping.
std::optional<std::string> trial_body_unsupported(const SceneSpec& scene);

/// A scene as the trial body reads it: owns the arrays FlatModel points into.
class FlatScene {
 public:
  /// Throws std::invalid_argument when trial_body_unsupported(scene) gives a reason.
  FlatScene(const SceneSpec& scene, DampingPolicy policy, const StopRules& rules);

  /// Pointers into this object's arrays (valid while it lives and is not moved).
  trial_body::FlatModel view() const;
  /// A trial's constants: TrialParams with SPEC 10's values resolved against the scene's.
  trial_body::TrialConsts constants(const TrialParams& trial) const;
  /// Doubles of state per trial: x, v, F, D' (3 per node each) and the safe accumulators.
  std::size_t state_doubles() const;

  int nodes() const { return static_cast<int>(fixed_.size()); }
  int springs() const { return static_cast<int>(spring_i_.size()); }

  // Every array of FlatModel, for the GPU sweep's copies.
  std::vector<int> spring_i_, spring_j_, incident_offset_, incident_;
  std::vector<double> rest_length_, kappa_scale_, kd_scale_, rest_, x0_, v0_, ext_;
  std::vector<double> anchor_scale_, anchor_kd_scale_, mass_scale_, gamma_scale_, kappa_max_scale_;
  std::vector<unsigned char> fixed_;

 private:
  Params base_;
  trial_body::FlatModel shape_;  // the scalars of view()
};

/// Runs `trials` one after another through the host copy of the trial body, each to its
/// verdict, and returns their results in order.
std::vector<TrialResult> run_trial_body(const FlatScene& scene,
                                        const std::vector<TrialParams>& trials);

}  // namespace dampbound
