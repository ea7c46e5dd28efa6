#pragma once
// The exact limits of the paper's step at non-uniform nodal rates (SPEC 7's symmetric index):
// the index lambda_max(dt^2 A + 2 dt C) at the scene, certified, and the largest gamma and dt
// at which it stays below 4, each by definite_root on one pattern analysis.
#include <memory>

#include "core/analysis/detail/exact_over_budget.hpp"
#include "core/analysis/linear_stability_exact.hpp"

namespace dampbound::detail {

class ShiftedCholesky;

/// Sets e's method, index, stability and (unless K is indefinite) gamma_hi and dt_max, each
/// root proved stable within 1e-10 relative of a value not proved so. `factors`: the
/// spectrum's, whose pattern analysis every index matrix shares (made here when empty).
void symmetric_index_limits(const ExactInputs& in, const Params& params,
                            const ExactOptions& options, ExactStability& e,
                            std::unique_ptr<ShiftedCholesky>& factors);

}  // namespace dampbound::detail
