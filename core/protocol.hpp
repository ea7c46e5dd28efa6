#pragma once
// The paper's experiment protocol (sec. 3, SPEC 5): perturb, step until restored, diverged,
// or the iteration limit; and the settled rule (SPEC 8): step to the limit and judge whether
// the run stayed below the restore threshold.
#include "core/export.hpp"
#include <array>
#include <functional>
#include <optional>
#include <string>

#include "core/step.hpp"

namespace dampbound DAMPBOUND_API {

/// Which verdict a run gives (SPEC 8).
enum class StopRule {
  first_entry,  ///< the paper's (SPEC 5): restored at the first iteration below the threshold
  settled,      ///< step to the limit: settled where it stayed below from some iteration on
};

const char* to_string(StopRule r);  ///< "first-entry" or "settled"
/// Parses "first-entry" or "settled"; nullopt for anything else.
std::optional<StopRule> parse_stop_rule(const std::string& text);

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

const char* to_string(Outcome o);

/// A rule's final verdicts: first-entry {restored, diverged, not_restored}, settled
/// {settled, diverged, not_settled}.
std::array<Outcome, 3> final_outcomes(StopRule rule);

/// The verdict after one step under the first-entry rule: diverged (a non-finite coordinate or
/// max displacement above the divergence threshold), restored (below the restore threshold),
/// not_restored at the iteration limit, else running.
Outcome judge(const StopRules& rules, const StepStats& stats);

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
/// calls this one function.
Outcome judge_band(const StopRules& rules, BandHistory& band, int iteration,
                   double max_displacement, bool finite);

/// What every runner reports about a run, the Session and the batched sweep kernel alike:
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

/// A Session's result: the TrialResult and what only a Session tracks while the run goes on.
struct RunResult : TrialResult {
  int below_since = 0;  ///< below the threshold since this iteration (0 if above): the settled
                        ///< candidate while a run goes on
  double time = 0;                 ///< simulated seconds
  long long unguaranteed = 0;        ///< node-steps with gamma_lo > gamma_safe (SPEC 9)
  long long compressed_springs = 0;  ///< spring-steps with l < l0: K may be indefinite (SPEC 9)
};

/// Adds one step's counts to `result` and judges it (no-op on the verdict once latched).
void accumulate(RunResult& result, const StepStats& stats, const StopRules& rules);

/// Sees every step of a run (Session::run_to_end).
using StepObserver = std::function<void(const StepSample&)>;

}  // namespace dampbound
