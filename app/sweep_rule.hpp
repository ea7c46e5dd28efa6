#pragma once
// What a sweep says about its verdict rule (SPEC 8): which one it runs, before it starts, and
// after a settled sweep what --rule first-entry would have cost instead, from the rows' own
// first entries.
#include <optional>
#include <string>
#include <vector>

#include "core/sweep/csv.hpp"

namespace dampbound::app {

/// One line for stderr before the sweep: the rule, its limit and the other rule.
std::string rule_intro(StopRule rule, int max_iterations);

/// After a settled sweep: "rule  settled: S trial-steps; --rule first-entry would stop each
/// trial at its first entry into the band: F trial-steps (P%, about T s at this rate)".
/// nullopt for a first-entry sweep or no rows. `seconds`: this run's time.
std::optional<std::string> rule_cost_line(const std::vector<SweepRow>& rows, StopRule rule,
                                          double seconds);

}  // namespace dampbound::app
