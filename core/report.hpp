#pragma once
// Traces and results as CSV and JSON (what `run --trace` and `run --json` print).
#include <iosfwd>
#include <string>
#include <vector>

#include "core/protocol.hpp"

namespace dampbound {

/// Header + one row per iteration: iteration, time, the watched node's displacement, lower and
/// upper bound, user and effective gamma, max displacement, counts, then the watched node's
/// gamma_safe and the counts of SPEC 9. Non-finite = "inf".
/// With a non-empty `run_label` a first column "run" holds it (figures with several runs).
void write_trace_csv(std::ostream& out, const std::vector<StepStats>& trace,
                     const std::string& run_label = "", bool header = true);

/// One JSON object: the scene name, the parameters, the outcome and the counts.
std::string result_json(const std::string& scene, const Params& params, const StopRules& rules,
                        int watched, const RunResult& result);

}  // namespace dampbound
