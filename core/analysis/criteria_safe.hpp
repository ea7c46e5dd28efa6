#pragma once
// SPEC 9's safe bound as rows of the criteria table.
#include <string>
#include <vector>

#include "core/analysis/criteria.hpp"

namespace dampbound {

/// "" for the paper's step, for which SPEC 9 is derived; for any other integrator the phrase
/// that says its numbers guarantee nothing there (every row and line that shows them adds it).
std::string safe_bound_scope(Integrator integrator);

/// The safe bound of SPEC 9 at the state (core/physics/safe_bound.hpp): gamma_safe (worst node, the
/// user's gamma_i judged), dt_safe at the user's gamma, and the nodes where critical damping
/// cannot be guaranteed (gamma_lo_i > gamma_safe_i). With `exact` (the paper's step) each
/// gives its ratio to the exact limit. Where a spring is compressed K may be indefinite, and
/// under any integrator but the paper's step SPEC 9 is not derived: the verdict is n/a and the
/// test says why.
std::vector<CriterionResult> safe_criteria(const Model& model, const State& state,
                                           const Params& params,
                                           const ExactStability* exact = nullptr);

}  // namespace dampbound
