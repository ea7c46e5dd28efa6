#pragma once
// A sweep's prediction checks as claims of the paper (for `dampbound reproduce`), beside the
// figures' claims of core/analysis/claims.hpp.
#include <string>
#include <vector>

#include "core/analysis/claims.hpp"
#include "core/sweep/summary.hpp"

namespace dampbound {

/// A sweep's prediction checks (core/sweep/summary.hpp) as claims of the paper's sec. 4:
/// holds when it held in every trial, partly when in some, does not hold when in none.
/// Checks whose text does not mention the paper (dampbound's own, e.g. SPEC 7) are skipped.
std::vector<Claim> sweep_claims(const std::vector<PredictionCheck>& checks,
                                const std::string& source, const std::string& grid);

/// One sweep's claims under both rules (SPEC 8), paired by position (the same checks of the
/// same grid run once per rule): a claim that a run is "not restored" (keeps oscillating) is
/// about lasting behaviour and judged by the settled rule, the others by the first entry;
/// each gives the other rule's count beside its own where they differ.
std::vector<Claim> both_rule_claims(const std::vector<Claim>& first_entry,
                                    const std::vector<Claim>& settled);

}  // namespace dampbound
