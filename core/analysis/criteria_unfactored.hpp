#pragma once
// The exact rows of the criteria table over the factorisation budget: nothing exact, but what
// plain Lanczos and Gershgorin prove without a factorisation (ExactStability::Unfactored,
// docs/criteria.md "Over the factorisation budget").
#include <vector>

#include "core/analysis/criteria.hpp"

namespace dampbound {

/// The four exact rows (lambda_max, spectral radius, gamma interval, dt limit) of `e`, which
/// was not computed (`!e.computed()`): each test begins with over_budget_test(e).
std::vector<CriterionResult> unfactored_criteria(const ExactStability& e, const Params& params);

}  // namespace dampbound
