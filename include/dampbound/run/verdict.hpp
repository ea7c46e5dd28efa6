#pragma once
// The protocol's rules and verdicts (SPEC 5, 8) and what a trial reports: plain data and the
// one verdict function, judge_band, which the GPU sweep's device code calls as well
// (include/dampbound/physics/host_device.hpp). include/dampbound/run/protocol.hpp builds the Session's side on these.
#include "dampbound/physics/export.hpp"
#include "dampbound/physics/host_device.hpp"

namespace dampbound DAMPBOUND_API {

/// Which verdict a run gives (SPEC 8).
enum class StopRule {
  first_entry,  ///< the paper's (SPEC 5): restored at the first iteration below the threshold
  settled,      ///< step to the limit: settled where it stayed below from some iteration on
};

/// When a run stops (SPEC 5, 8). Thresholds are relative to the perturbation's magnitude.
struct StopRules {
  double reference = 5.0;          ///< the perturbation magnitude (cm)
  double restore_fraction = 0.01;  ///< restored when max_i |x_i - X_i| < fraction * reference
  double diverge_factor = 100;     ///< diverged when max_i |x_i - X_i| > factor * reference
  int max_iterations = 1000;       ///< not restored at this iteration
  /// The one default rule of every command and API (SPEC 8); what reproduces the paper (fig1,
  /// fig2, reproduce, the sweep presets) names first-entry explicitly.
  StopRule rule = StopRule::settled;
};

inline StopRules default_stop_rules() { return StopRules{}; }

/// restored and not_restored are the first-entry rule's verdicts; settled and not_settled the
/// settled rule's; diverged is either's.
enum class Outcome { running, restored, diverged, not_restored, settled, not_settled };

/// A run's history against the restore threshold (SPEC 8), kept after every step. Iterations
/// count from 1; 0 means "none".
struct BandHistory {
  int first_entry = 0;  ///< first iteration below the threshold (the paper's restored)
  int left_at = 0;      ///< first iteration at or above it after an entry
  int below_since = 0;  ///< the iteration from which it has been below until now; 0 if above
};

/// Records iteration `iteration` (max displacement `max_displacement` cm, `finite` when every
/// coordinate is) in `band` and returns the verdict under rules.rule: diverged whenever the
/// divergence test of SPEC 5 fires; first-entry: restored at the first entry, not_restored at
/// the limit; settled: at the limit settled when below there (since band.below_since), else
/// not_settled. Returns running otherwise. Every verdict path (Session, the batched kernel)
/// calls this one function, the GPU sweep's device code too.
DAMPBOUND_HD inline Outcome judge_band(const StopRules& rules, BandHistory& band, int iteration,
                                      double max_displacement, bool finite) {
  // The comparisons are written so that a NaN falls to diverged, never below the threshold.
  if (!finite || !(max_displacement <= rules.diverge_factor * rules.reference))
    return Outcome::diverged;
  const bool below = max_displacement < rules.restore_fraction * rules.reference;
  if (below) {
    if (band.first_entry == 0) band.first_entry = iteration;
    if (band.below_since == 0) band.below_since = iteration;
  } else {
    if (band.first_entry != 0 && band.left_at == 0) band.left_at = iteration;
    band.below_since = 0;
  }
  if (rules.rule == StopRule::first_entry) {
    if (below) return Outcome::restored;
    return iteration >= rules.max_iterations ? Outcome::not_restored : Outcome::running;
  }
  // SPEC 8: no proof that a run below the threshold stays there, so it steps to the limit.
  if (iteration < rules.max_iterations) return Outcome::running;
  return below ? Outcome::settled : Outcome::not_settled;
}

/// What every runner reports about a run (Session, the batched kernel, the GPU sweep alike):
/// the verdict, its band history (SPEC 8) and the counts. A sweep's CSV row is made of it.
struct TrialResult {
  Outcome outcome = Outcome::running;
  int iterations = 0;              ///< the iteration at which the outcome was reached
  int first_entry = 0;  ///< first iteration below the restore threshold; 0 = none yet
  int left_at = 0;      ///< first iteration back at or above it after an entry; 0 = none
  int settled_at = 0;   ///< settled rule: from here on below the threshold to the limit; 0 = none
  double max_displacement = 0;     ///< max_i |x_i - X_i| at the last iteration (inf if not finite)
  long long violations = 0;        ///< node-steps whose effective gamma was outside the bounds
  long long unstabilisable = 0;    ///< node-steps with gamma_lo > gamma_hi
  long long clamped = 0;           ///< node-steps whose gamma the policy changed
  long long zero_length_springs = 0;
};

}  // namespace dampbound
