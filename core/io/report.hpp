#pragma once
// Traces and results as CSV and JSON (what `run --trace` and `run --json` print).
#include <iosfwd>
#include <string>
#include <vector>

#include "core/physics/damping_ratio.hpp"
#include "dampbound/run/protocol.hpp"

namespace dampbound {

/// Header + one row per iteration: iteration, time, the watched node's displacement, lower and
/// upper bound, user and effective gamma, max displacement, counts, then the watched node's
/// gamma_safe and the counts of SPEC 9. Non-finite = "inf".
/// With a non-empty `run_label` a first column "run" holds it (figures with several runs).
void write_trace_csv(std::ostream& out, const std::vector<StepSample>& trace,
                     const std::string& run_label = "", bool header = true);

/// The verdict in one line, the outcome and its iteration first: "settled at 112, checked to
/// 1000"; "settled at 260, checked to 1000 (entered the 1% band at 230, left it at 231)"; "not
/// settled, checked to 1000 (never entered the 1% band)"; "diverged at 40"; "restored at 112
/// (first entry into the 1% band, the paper's rule)". While the run goes on: "running", with
/// the entry and exit so far.
std::string verdict_text(const RunResult& result, const StopRules& rules);

/// The verdict in a few words, for legends and tables: "running", "settled at N", "not settled
/// at N (entered at K, left at L)", "diverged at N", "restored at N", "not restored at N", and
/// while running after an exit "running (entered at K, left at L)".
std::string verdict_short(const RunResult& result);

/// The nodal damping ratio for a person: "1" where every free node has the same, "0.5..1"
/// otherwise, "none" where no node has one.
std::string zeta_text(const DampingRatioRange& zeta);

/// One JSON object: the scene name, the parameters, the outcome and the counts; the rule and
/// the band history (first_entry, left_at, settled_at: null where none, SPEC 8).
/// `zeta` (optional): the range of the nodal damping ratio gamma_i / gamma_lo_i over the free
/// nodes (damping_ratio_range()), written beside gamma as zeta_min and zeta_max.
std::string result_json(const std::string& scene, const Params& params, const StopRules& rules,
                        int watched, const RunResult& result,
                        const DampingRatioRange* zeta = nullptr);

}  // namespace dampbound
