#pragma once
// Scene expectations ([[expect]] in a scene file): run what they refer to and judge them.
#include <string>
#include <vector>

#include "dampbound/run/scene.hpp"

namespace dampbound {

/// One judged assertion, e.g. "outcome == restored" measured "restored at 34".
struct ExpectationResult {
  std::string scene;     ///< scene file
  int line = 0;          ///< line of the [[expect]] table
  std::string run;       ///< run label ("" = the scene's own parameters)
  std::string what;      ///< the assertion with its rule, e.g. "[settled] settled_at in [30, 40]"
  std::string measured;  ///< what the run gave
  bool pass = false;
};

/// The result of the scene's own parameters ("") or of the [[run]] with that label, judged by
/// `rule` (SPEC 5 first entry or SPEC 8 settled); `to_the_limit`: without SPEC 8's early stop,
/// so that a settled run's final displacement, counts and iterations are those at the limit.
RunResult run_labelled(const SceneSpec& scene, const std::string& label,
                       StopRule rule = StopRule::first_entry, bool to_the_limit = false);

/// Runs every run the scene's expectations refer to (each once) and judges every field of
/// every expectation. Empty when the scene declares none.
std::vector<ExpectationResult> check_expectations(const SceneSpec& scene);

}  // namespace dampbound
