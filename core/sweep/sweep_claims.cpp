#include "core/sweep/sweep_claims.hpp"

#include "core/io/format.hpp"

namespace dampbound {

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
    c_snprintf(buf, sizeof buf, "%.1f%%", pct);
    c.measured = "held in " + std::to_string(p.held) + " of " + std::to_string(p.of) +
                 " trials (" + buf + ") on " + grid;
    c.rule = p.claim.find("[settled rule]") == std::string::npos ? StopRule::first_entry
                                                                  : StopRule::settled;
    c.verdict = p.held == p.of ? ClaimVerdict::holds
                : p.held == 0  ? ClaimVerdict::does_not_hold
                               : ClaimVerdict::partly;
    out.push_back(c);
  }
  return out;
}

std::vector<Claim> both_rule_claims(const std::vector<Claim>& first_entry,
                                    const std::vector<Claim>& settled) {
  std::vector<Claim> out;
  for (size_t k = 0; k < first_entry.size(); ++k) {
    const Claim& f = first_entry[k];
    if (k >= settled.size()) {
      out.push_back(f);
      continue;
    }
    const Claim& s = settled[k];
    const bool lasting = f.paper.find("not restored") != std::string::npos;
    Claim c = lasting ? s : f;
    c.paper = f.paper;  // the paper's words, as the first-entry check states them
    if (lasting)
      c.measured = "settled rule: " + s.measured + "; first entry: " + f.measured;
    else if (s.measured != f.measured)
      c.measured = f.measured + "; settled rule: " + s.measured;
    out.push_back(c);
  }
  return out;
}

}  // namespace dampbound
