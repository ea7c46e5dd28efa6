#pragma once
// The scene's half of SPEC 8's early stop (core/run/detail/settle_bound.hpp; the proof in
// docs/settled.md): which scenes the certificate covers and their constants, built once from the
// ModelSpec, and the arrays the norm reads. Session, the batched kernel and the trial body's
// FlatScene each build one from the same ModelSpec, so all three decide alike.
#include <optional>
#include <string>
#include <vector>

#include "core/run/detail/settle_bound.hpp"
#include "dampbound/physics/model.hpp"

namespace dampbound {

class SettleProof {
 public:
  /// The scene `model`, run from positions `x0` and velocities `v0` (3 per node) with
  /// `integrator` and `policy`; `other_damping`: SPEC 10's dashpots or Rayleigh terms, `cuts`:
  /// the run cuts springs later. Either makes the scene ineligible, as do the rest of
  /// why_not()'s reasons.
  SettleProof(const ModelSpec& model, const std::vector<double>& x0,
              const std::vector<double>& v0, Integrator integrator, DampingPolicy policy,
              bool other_damping, bool cuts);

  /// Why the certificate does not cover the scene (nullopt when it does): its settled runs
  /// then step to the limit.
  const std::optional<std::string>& why_not() const { return why_not_; }
  const settle::SceneBound& bound() const { return bound_; }
  /// Pointers into this object's arrays (valid while it lives and is not moved).
  settle::SceneArrays arrays() const;
  /// A trial's certificate (settle::trial_bound with this scene's constants).
  settle::TrialBound trial(double m, double kappa, double gamma, double dt,
                           const StopRules& rules) const;

 private:
  std::optional<std::string> why_not_;
  settle::SceneBound bound_;
  std::vector<int> spring_i_, spring_j_;
  std::vector<double> kappa_scale_, rest_, anchor_scale_, direction_;
  std::vector<unsigned char> fixed_;
};

/// The scene constants of the certificate (SettleProof's bound()), or why it does not cover the
/// scene. Exposed for the trial body's FlatScene, which keeps its own arrays.
settle::SceneBound settle_scene_bound(const ModelSpec& model, const std::vector<double>& x0,
                                      const std::vector<double>& v0, Integrator integrator,
                                      DampingPolicy policy, bool other_damping, bool cuts,
                                      std::optional<std::string>* why_not = nullptr);

/// Process-wide switch for the early stop (on by default): the tests and the benchmark turn it
/// off to run every settled trial to its limit and compare. Read when a Session, kernel or
/// FlatScene is built.
void set_settle_proof_enabled(bool on);
bool settle_proof_enabled();
/// Multiplies every SettleProof::trial()'s radius (1 by default): only for the test that shows
/// a weakened certificate changes verdicts (tests/core/run/settle_proof_test.cpp).
void set_settle_proof_widen(double factor);

}  // namespace dampbound
