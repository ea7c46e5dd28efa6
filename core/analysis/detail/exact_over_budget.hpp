#pragma once
// What exact_stability's two routes share (linear_stability_exact.cpp): its inputs, and the
// route over the factorisation budget, which factorises nothing and reports what plain
// Lanczos and Gershgorin prove without a factorisation (ExactStability::Unfactored).
#include <Eigen/Core>
#include <vector>

#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "dampbound/analysis/linear_stability.hpp"

namespace dampbound::detail {

/// The inputs every method shares: A = M^-1/2 K M^-1/2 at x and the damping rates
/// r_i = gamma_i / (gamma m_i) per free dof, with their extremes.
struct ExactInputs {
  SparseMatrix A;
  Eigen::VectorXd R;
  double r_min = 0, r_max = 0;
};

/// Whether every damping rate is the same (to 1e-12): then every mode is a scalar recurrence.
inline bool uniform_rates(const ExactInputs& in) {
  return in.r_max - in.r_min <= 1e-12 * in.r_max;
}

/// Over the budget: nothing factorised, every exact number NaN, the prediction and the budget
/// kept for the report; and what plain Lanczos and Gershgorin prove without a factorisation
/// (ExactStability::Unfactored).
ExactStability over_budget(const Model& model, const std::vector<Vec3>& x, const ExactInputs& in,
                           const Params& params, const ExactOptions& options,
                           const FactorisationOverBudget& over);

}  // namespace dampbound::detail
