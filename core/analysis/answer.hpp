#pragma once
// The answer first (docs/cli.md, "The answer first"): one or two lines a person can quote,
// the verdict at the given parameters, the limits that matter and what to change, built only
// from numbers the analysis, the suggestion or the run already holds (no verdict of its own).
// `bounds`, `suggest` and `run` print them before their evidence; the Python results' repr
// says the same.
#include <string>
#include <vector>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/substeps.hpp"
#include "core/analysis/suggest.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/run/protocol.hpp"

namespace dampbound {

/// The exact analysis at `p` (its gamma and dt; nullptr: the lines without them): stable or not (or not decided over the
/// factorisation budget), the largest stable dt at this gamma and the stable gamma range at
/// this dt; `safe` (nullable) adds SPEC 9's gamma and dt that guarantee it node by node
/// (pass it only where the safe bound applies to the integrator). `where`: the linearisation
/// point in words ("at rest").
std::vector<std::string> exact_answer(const ExactStability& e, const Params* p,
                                      const SafeBoundSummary* safe, const std::string& where);

/// suggest with a dt: the gamma to use (and whether its run settled), the stable range.
std::vector<std::string> damping_answer(const DampingSuggestion& s);
/// suggest with a gamma: the dt to use (and whether its run settled), the exact limit.
std::vector<std::string> step_answer(const StepSuggestion& s);
/// suggest --frame-dt: the substeps per frame to use, or why there is none.
std::vector<std::string> substeps_answer(const SubstepSuggestion& s);

/// run: the verdict at the run's gamma and dt and its time; for a run that did not settle,
/// what to try.
std::vector<std::string> run_answer(const RunResult& r, const StopRules& rules, const Params& p);

}  // namespace dampbound
