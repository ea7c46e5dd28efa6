#pragma once
// The paper's claims, each beside what dampbound measured and whether it holds (for
// `dampbound reproduce`). Claims are judged from measured data only; nothing is tuned.
#include <iosfwd>
#include <string>
#include <vector>

#include "core/analysis/figures.hpp"
#include "dampbound/run/protocol.hpp"

namespace dampbound {

enum class ClaimVerdict { holds, does_not_hold, partly };
const char* to_string(ClaimVerdict v);

struct Claim {
  std::string source;    ///< where the paper says it ("sec. 4, Fig. 1")
  std::string paper;     ///< the claim in the paper's words
  std::string measured;  ///< what dampbound measured, with numbers
  ClaimVerdict verdict = ClaimVerdict::does_not_hold;
  /// The verdict rule that judges the claim (SPEC 8): "first-entry" for what the paper's
  /// protocol measures, "settled" for claims about what a run does for good.
  StopRule rule = StopRule::first_entry;
};

/// Each run of a figure judged again by the settled rule (SPEC 8): the same scene, parameters
/// and iteration limit, stepped to the limit. In the order of fig.runs.
std::vector<RunResult> settled_results(const SceneSpec& scene, const FigureData& fig);

/// Both verdicts of one run: "restored at K (first entry); settled rule: ..." or, where they
/// agree, one of them.
std::string both_verdicts(const FigureRun& run, const RunResult& settled);

/// Fig. 1 (runs 0.0005, 0.001, 0.002; `settled` from settled_results): "keeps oscillating"
/// below the lower bound, judged by the settled rule; "steady state after 34" at it, judged
/// by the first entry, with the settled verdict beside it where they differ.
std::vector<Claim> fig1_claims(const FigureData& fig1, const std::vector<RunResult>& settled);

/// Fig. 2 (factor 1.0, 1.05): "stable within 652 iterations and remained stable thereafter"
/// and "5% above, unstable", both claims about what the run does for good: settled rule.
std::vector<Claim> fig2_claims(const FigureData& fig2, const std::vector<RunResult>& settled);

/// Markdown table of the claims, with the rule that judges each.
void write_claims_table(std::ostream& out, const std::vector<Claim>& claims);

}  // namespace dampbound
