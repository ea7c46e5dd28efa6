#pragma once
// The paper's experiment protocol (sec. 3, SPEC 5): perturb, step until restored, diverged,
// or the iteration limit; and the settled rule (SPEC 8): step to the limit and judge whether
// the run stayed below the restore threshold.
#include "dampbound/physics/export.hpp"
#include <array>
#include <functional>
#include <optional>
#include <string>

#include "dampbound/physics/step.hpp"
#include "dampbound/run/verdict.hpp"

namespace dampbound DAMPBOUND_API {

const char* to_string(StopRule r);  ///< "first-entry" or "settled"
/// Parses "first-entry" or "settled"; nullopt for anything else.
std::optional<StopRule> parse_stop_rule(const std::string& text);

const char* to_string(Outcome o);

/// A rule's final verdicts: first-entry {restored, diverged, not_restored}, settled
/// {settled, diverged, not_settled}.
std::array<Outcome, 3> final_outcomes(StopRule rule);

/// The verdict after one step under the first-entry rule: diverged (a non-finite coordinate or
/// max displacement above the divergence threshold), restored (below the restore threshold),
/// not_restored at the iteration limit, else running.
Outcome judge(const StopRules& rules, const StepStats& stats);

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
