#pragma once
// RK4's per-mode certificates (SPEC 7's classic step at a uniform damping rate c, step h):
// the step's eigenvalues are R(h mu), mu the roots of mu^2 + c mu + lambda. Used by
// mode_instability and mode_stability (linear_stability_modes.hpp); e1 = 1 + 1e-12, the
// radius that counts as unstable. docs/criteria.md, "Over the factorisation budget".
#include <limits>
#include <utility>

namespace dampbound::detail {

/// The per-mode proofs' closed forms take a few roundings each: every threshold is moved by
/// this factor toward the side it proves.
constexpr double kRoundUp = 1 + 8 * std::numeric_limits<double>::epsilon();

/// The smallest lambda (>= c^2/4) from which every mode is certified unstable (radius above
/// e1) at rate c and step h; inf when none up to h^2 (lambda - c^2/4) = 1e12 is.
double rk4_lambda_from(double c, double h, double e1);

/// The rates proved stable at step h, every mode in [0, lambda_hi]: [lo, hi] around c; where c
/// itself is not proved, around the proved one of 31 rates evenly across (0, 2.78529/h)
/// nearest to c (then c lies outside it); none (lo > hi) when none of those is proved.
std::pair<double, double> rk4_rate_range(double lambda_hi, double c, double h, long double e1);

/// The largest step S found such that every step in (0, S] is proved stable at rate c, every
/// mode in [0, lambda_hi]; 0 when none is.
double rk4_dt_up_to(double lambda_hi, double c, long double e1);

}  // namespace dampbound::detail
