#pragma once
// Substeps per frame: the control engines give their users (Warp's sim_substeps, Blender's
// quality steps). For a frame time F, the fewest n such that dt = F/n is stable by the exact
// limit of the integrator (SPEC 7), and the n that the safe bound (SPEC 9) guarantees, each run
// to a verdict under the settled rule (SPEC 8).
#include <string>

#include "core/analysis/suggest.hpp"

namespace dampbound {

/// One substep count: n, its dt = F/n, and the run that checks it.
struct SubstepCount {
  int n = 0;        ///< 0: no count (the limit is not known, or needs more than kMaxSubsteps)
  double dt = 0;    ///< F / n (s)
  double limit = 0; ///< the dt limit it comes from (s; exclusive)
  bool ran = false;  ///< a verification run was made
  VerifiedRun run;  ///< its verdict; run.verified() says whether it settled
};

struct SubstepSuggestion {
  double frame_dt = 0;
  SubstepCount exact;  ///< from the exact limit at the user's gamma (rest state)
  SubstepCount safe;   ///< from min_i dt_safe_i at the user's gamma_i (rest state)
  std::string note;    ///< why a count is missing, "" otherwise
};

/// The largest substep count considered (a frame cut finer than this is reported, not run).
inline constexpr int kMaxSubsteps = 1000000;

/// The fewest n >= 1 with frame_dt / n < limit (limit exclusive); 0 when limit is not a
/// positive number or n would exceed kMaxSubsteps.
int substeps_below(double frame_dt, double limit);

/// The substeps of `params` (its gamma; its dt is replaced by frame_dt / n) on the scene, both
/// counts verified by verify_run() when `verify` is set.
SubstepSuggestion suggest_substeps(const SceneSpec& scene, const Params& params,
                                   const StopRules& rules, double frame_dt, bool verify = true);

}  // namespace dampbound
