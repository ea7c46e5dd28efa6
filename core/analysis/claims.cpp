#include "core/analysis/claims.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>

#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound {

const char* to_string(ClaimVerdict v) {
  switch (v) {
    case ClaimVerdict::holds: return "holds";
    case ClaimVerdict::does_not_hold: return "does not hold";
    case ClaimVerdict::partly: return "partly";
  }
  return "?";
}

namespace {
bool settled(const RunResult& r) { return r.outcome == Outcome::settled; }
}  // namespace

std::vector<RunResult> settled_results(const SceneSpec& scene, const FigureData& fig) {
  std::vector<RunResult> out;
  for (const FigureRun& run : fig.runs) {
    StopRules rules = run.rules;
    rules.rule = StopRule::settled;
    Session session(scene, run.params, rules);
    out.push_back(session.run_to_end());
  }
  return out;
}

std::string both_verdicts(const FigureRun& run, const RunResult& s) {
  const RunResult& p = run.result;
  StopRules rules = run.rules;
  rules.rule = StopRule::settled;
  // The rules agree when the first entry is for good, or when neither entered nor settled.
  const bool agree = (p.outcome == Outcome::restored && settled(s) && s.settled_at == p.iterations) ||
                     (p.outcome == Outcome::diverged && s.outcome == Outcome::diverged &&
                      s.iterations == p.iterations);
  if (agree && p.outcome == Outcome::restored)
    return verdict_short(p) + " and settled there, below the band to the limit " +
           std::to_string(rules.max_iterations) + " (both rules)";
  if (agree) return verdict_short(p) + " (both rules)";
  return verdict_short(p) + " by the first entry; settled rule: " + verdict_text(s, rules);
}

std::vector<Claim> fig1_claims(const FigureData& fig, const std::vector<RunResult>& st) {
  std::vector<Claim> out;
  // Runs 0 and 1 are below the lower bound (0.0005, 0.001), run 2 is at it (0.002).
  const RunResult& r2 = fig.runs.at(2).result;
  Claim below;
  below.source = "sec. 4, Fig. 1";
  below.rule = StopRule::settled;
  below.paper = "Below the lower bound (gamma = 0.0005, 0.001 < 0.002) the mesh keeps "
                "oscillating and never returns to its initial configuration";
  below.measured = "gamma = 0.0005: " + both_verdicts(fig.runs.at(0), st.at(0)) +
                   "; gamma = 0.001: " + both_verdicts(fig.runs.at(1), st.at(1));
  const int settled_below = settled(st.at(0)) + settled(st.at(1));
  below.verdict = settled_below == 0   ? ClaimVerdict::holds
                  : settled_below == 2 ? ClaimVerdict::does_not_hold
                                       : ClaimVerdict::partly;
  out.push_back(below);
  Claim at;
  at.source = "sec. 4, Fig. 1";
  at.paper = "At the lower bound (gamma = 0.002) the mesh reaches steady state after 34 "
             "iterations";
  at.measured = "gamma = 0.002: " + both_verdicts(fig.runs.at(2), st.at(2));
  at.verdict = r2.outcome == Outcome::restored && r2.iterations == 34 ? ClaimVerdict::holds
               : r2.outcome == Outcome::restored                     ? ClaimVerdict::partly
                                                                     : ClaimVerdict::does_not_hold;
  if (at.verdict == ClaimVerdict::partly)
    at.measured += " (it settles, after " + std::to_string(r2.iterations) + ", not 34)";
  out.push_back(at);
  return out;
}

std::vector<Claim> fig2_claims(const FigureData& fig, const std::vector<RunResult>& st) {
  std::vector<Claim> out;
  const RunResult &s0 = st.at(0), &s1 = st.at(1);
  Claim at;
  at.source = "sec. 4, Fig. 2";
  at.rule = StopRule::settled;
  at.paper = "With damping equal to the upper bound (eq. 6) the system achieved stability "
             "within 652 iterations and remained stable thereafter";
  at.measured = "factor 1.0: " + both_verdicts(fig.runs.at(0), s0);
  // Holds when it settled by 652 (below the band from there to the limit); partly when it
  // settled later, or entered by 652 but did not settle.
  const bool by_652 = settled(s0) && s0.settled_at <= 652;
  const bool entered_by_652 = s0.first_entry > 0 && s0.first_entry <= 652;
  at.verdict = by_652                            ? ClaimVerdict::holds
               : settled(s0) || entered_by_652   ? ClaimVerdict::partly
                                                 : ClaimVerdict::does_not_hold;
  out.push_back(at);
  Claim above;
  above.source = "sec. 4, Fig. 2";
  above.rule = StopRule::settled;
  above.paper = "With damping 5% above the upper bound the system was unstable";
  above.measured = "factor 1.05: " + both_verdicts(fig.runs.at(1), s1);
  above.verdict = s1.outcome == Outcome::diverged ? ClaimVerdict::holds
                  : settled(s1)                   ? ClaimVerdict::does_not_hold
                                                  : ClaimVerdict::partly;
  out.push_back(above);
  return out;
}

void write_claims_table(std::ostream& out, const std::vector<Claim>& claims) {
  out << "| # | Source | The paper says | dampbound measured | Rule | Verdict |\n"
         "|---|---|---|---|---|---|\n";
  int k = 1;
  for (const Claim& c : claims)
    out << "| " << k++ << " | " << c.source << " | " << c.paper << " | " << c.measured << " | "
        << to_string(c.rule) << " | **" << to_string(c.verdict) << "** |\n";
}

}  // namespace dampbound
