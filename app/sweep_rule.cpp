#include "app/sweep_rule.hpp"

#include "core/io/format.hpp"

namespace dampbound::app {

std::string rule_intro(StopRule rule, int max_iterations) {
  if (rule == StopRule::settled)
    return "rule settled: every trial steps to its limit (" + std::to_string(max_iterations) +
           " iterations) unless it diverges; --rule first-entry (the paper's) stops each at its "
           "first entry into the band, usually far sooner";
  return "rule first-entry (the paper's): each trial stops at its first entry into the band; "
         "--rule settled steps every trial to its limit (" +
         std::to_string(max_iterations) + " iterations) and judges where it stays";
}

std::optional<std::string> rule_cost_line(const std::vector<SweepRow>& rows, StopRule rule,
                                          double seconds) {
  if (rule != StopRule::settled || rows.empty()) return std::nullopt;
  double steps = 0, first = 0;
  for (const SweepRow& r : rows) {
    steps += r.iterations;
    // Under first-entry a trial stops at its first entry; one that never entered runs as here.
    first += r.first_entry > 0 && r.first_entry < r.iterations ? r.first_entry : r.iterations;
  }
  if (!(steps > 0)) return std::nullopt;
  const double share = first / steps;
  return "rule         settled: " + format_human(steps) + " trial-steps; --rule first-entry "
         "would stop each trial at its first entry into the band: " + format_human(first) +
         " trial-steps (" + format_digits(100 * share, 3) + "%, about " +
         format_digits(seconds * share, 3) + " s at this rate)";
}

}  // namespace dampbound::app
