#include "core/claims.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>

#include "core/io.hpp"
#include "core/session.hpp"

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
std::string outcome_text(const RunResult& r) {
  return std::string(to_string(r.outcome)) + " at iteration " + std::to_string(r.iterations);
}
}  // namespace

AfterRestore run_after_restore(const SceneSpec& scene, const FigureRun& run, int until) {
  Session session(scene, run.params, run.rules);
  const RunResult r = session.run_to_end();
  AfterRestore a;
  a.until = until;
  a.threshold = run.rules.restore_fraction * run.rules.reference;
  a.restored = r.outcome == Outcome::restored;
  a.restored_at = r.iterations;
  if (!a.restored) return a;
  while (session.state().iteration < until) {
    const StepStats& st = session.step_once();
    const Outcome o = judge(run.rules, st);
    if (o == Outcome::diverged) {
      a.diverged = true;
      a.diverged_at = st.iteration;
      break;
    }
    a.max_after = std::max(a.max_after, st.max_displacement);
  }
  return a;
}

std::vector<Claim> fig1_claims(const FigureData& fig) {
  std::vector<Claim> out;
  // Runs 0 and 1 are below the lower bound (0.0005, 0.001), run 2 is at it (0.002).
  const RunResult &r0 = fig.runs.at(0).result, &r1 = fig.runs.at(1).result,
                  &r2 = fig.runs.at(2).result;
  Claim below;
  below.source = "sec. 4, Fig. 1";
  below.paper = "Below the lower bound (gamma = 0.0005, 0.001 < 0.002) the mesh keeps "
                "oscillating and never returns to its initial configuration";
  below.measured = "gamma = 0.0005: " + outcome_text(r0) + "; gamma = 0.001: " + outcome_text(r1);
  const int settled = (r0.outcome == Outcome::restored) + (r1.outcome == Outcome::restored);
  below.verdict = settled == 0 ? ClaimVerdict::holds : settled == 2 ? ClaimVerdict::does_not_hold
                                                               : ClaimVerdict::partly;
  out.push_back(below);
  Claim at;
  at.source = "sec. 4, Fig. 1";
  at.paper = "At the lower bound (gamma = 0.002) the mesh reaches steady state after 34 "
             "iterations";
  at.measured = "gamma = 0.002: " + outcome_text(r2);
  at.verdict = r2.outcome == Outcome::restored && r2.iterations == 34 ? ClaimVerdict::holds
               : r2.outcome == Outcome::restored                     ? ClaimVerdict::partly
                                                                     : ClaimVerdict::does_not_hold;
  if (at.verdict == ClaimVerdict::partly)
    at.measured += " (it settles, after " + std::to_string(r2.iterations) + ", not 34)";
  out.push_back(at);
  return out;
}

std::vector<Claim> fig2_claims(const FigureData& fig, const AfterRestore& after) {
  std::vector<Claim> out;
  const RunResult &r0 = fig.runs.at(0).result, &r1 = fig.runs.at(1).result;
  Claim at;
  at.source = "sec. 4, Fig. 2";
  at.paper = "With damping equal to the upper bound (eq. 6) the system achieved stability "
             "within 652 iterations and remained stable thereafter";
  at.measured = "factor 1.0: " + outcome_text(r0);
  if (after.restored)
    at.measured += after.diverged ? "; stepped on, it diverged at iteration " +
                                        std::to_string(after.diverged_at)
                                  : "; stepped on to iteration " + std::to_string(after.until) +
                                        ", the largest displacement after the restore was " +
                                        format_number(after.max_after) + " cm";
  const bool within = r0.outcome == Outcome::restored && r0.iterations <= 652;
  const bool stays = after.restored && !after.diverged;
  at.verdict = within && stays ? ClaimVerdict::holds : (within || stays) ? ClaimVerdict::partly
                                                                    : ClaimVerdict::does_not_hold;
  out.push_back(at);
  Claim above;
  above.source = "sec. 4, Fig. 2";
  above.paper = "With damping 5% above the upper bound the system was unstable";
  above.measured = "factor 1.05: " + outcome_text(r1);
  above.verdict = r1.outcome == Outcome::diverged ? ClaimVerdict::holds : ClaimVerdict::does_not_hold;
  out.push_back(above);
  return out;
}

std::vector<Claim> sweep_claims(const std::vector<PredictionCheck>& checks,
                                const std::string& source, const std::string& grid) {
  std::vector<Claim> out;
  for (const PredictionCheck& p : checks) {
    if (p.claim.find("paper") == std::string::npos || p.of == 0) continue;
    Claim c;
    c.source = source;
    c.paper = p.claim;
    const double pct = 100.0 * static_cast<double>(p.held) / static_cast<double>(p.of);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f%%", pct);
    c.measured = "held in " + std::to_string(p.held) + " of " + std::to_string(p.of) +
                 " trials (" + buf + ") on " + grid;
    c.verdict = p.held == p.of ? ClaimVerdict::holds
                : p.held == 0  ? ClaimVerdict::does_not_hold
                               : ClaimVerdict::partly;
    out.push_back(c);
  }
  return out;
}

void write_claims_table(std::ostream& out, const std::vector<Claim>& claims) {
  out << "| # | Source | The paper says | dampbound measured | ClaimVerdict |\n"
         "|---|---|---|---|---|\n";
  int k = 1;
  for (const Claim& c : claims)
    out << "| " << k++ << " | " << c.source << " | " << c.paper << " | " << c.measured << " | **"
        << to_string(c.verdict) << "** |\n";
}

}  // namespace dampbound
