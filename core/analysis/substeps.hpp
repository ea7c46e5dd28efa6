#pragma once
// Substeps per frame: the control engines give their users (Warp's sim_substeps, Blender's
// quality steps). For a frame time F, the fewest n such that dt = F/n is stable by the exact
// limit of the integrator (SPEC 7, 10), and the n that the safe bound (SPEC 9) guarantees, each
// run from the scene's start to a verdict under the settled rule (SPEC 8) over the scene's
// simulated time. Both limits hold at
// rest; a run passes through states whose tangent stiffness (and with it Rayleigh damping's
// K(x)) is larger, where a count at the limit can still diverge or keep growing. Then the
// fewest count whose run settles is searched for by running.
#include <string>

#include "core/analysis/suggest.hpp"

namespace dampbound {

/// One substep count: n, its dt = F/n, and the run that checks it.
struct SubstepCount {
  int n = 0;        ///< 0: no count (the limit is not known, or needs more than kMaxSubsteps)
  double dt = 0;    ///< F / n (s)
  double limit = 0; ///< the dt limit it comes from (s; exclusive); 0 for a count found by running
  bool ran = false;  ///< a verification run was made
  VerifiedRun run;  ///< its verdict (settled rule)
  /// The count is verified when its run settles (SPEC 8): a run that neither settles nor
  /// diverges within the iteration limit proves nothing either way.
  bool verified() const { return ran && run.verified(); }
};

struct SubstepSuggestion {
  double frame_dt = 0;
  SubstepCount exact;  ///< from the exact limit at the user's gamma (rest state)
  SubstepCount safe;   ///< from min_i dt_safe_i at the user's gamma_i (rest state)
  /// Searched only when the exact count's run did not settle: the fewest count above it found
  /// to settle by running (n = 0 when none did within the search).
  SubstepCount by_running;
  int failed_at_most = 0;  ///< the largest count whose run did not settle in that search
  int search_runs = 0;     ///< runs the search made
  std::string note;    ///< why a count is missing, "" otherwise
  /// The count to use: the fewest verified one (the exact count, else the one found by
  /// running, else the safe count); nullptr when none was run or none settled.
  const SubstepCount* answer() const;
};

/// The largest substep count considered (a frame cut finer than this is reported, not run).
inline constexpr int kMaxSubsteps = 1000000;
/// The search by running makes at most this many runs, over counts up to
/// kSearchSpan times the exact count.
inline constexpr int kMaxSearchRuns = 16;
inline constexpr int kSearchSpan = 8;

/// A count's run covers the scene's simulated time (its iteration limit at its own dt), so
/// that a finer step is not judged over a shorter time: max_iterations, or horizon / dt
/// iterations where that is more, up to kVerifySpan times max_iterations.
inline constexpr int kVerifySpan = 4;
int verify_iterations(int max_iterations, double horizon, double dt);

/// "1 substep", "N substeps": how every output names a count.
std::string substeps_text(int n);

/// The fewest n >= 1 with frame_dt / n < limit (limit exclusive); 0 when limit is not a
/// positive number or n would exceed kMaxSubsteps.
int substeps_below(double frame_dt, double limit);

/// The substeps of `params` (its gamma; its dt is replaced by frame_dt / n) on the scene. With
/// options.verify both counts are run (and, when the exact count does not settle, the search
/// by running); options.progress is called before the analysis and each run, and stops the call
/// with SuggestCancelled when it returns false. options.verify = false gives the counts alone.
SubstepSuggestion suggest_substeps(const SceneSpec& scene, const Params& params,
                                   const StopRules& rules, double frame_dt,
                                   const SuggestOptions& options = {});

}  // namespace dampbound
