#pragma once
// SPEC 7's closed forms for the paper's semi-implicit Euler step with uniform c = gamma/m:
// the damping and step limits from the largest eigenvalue lambda_max of M^-1 K.
#include "dampbound/physics/export.hpp"

namespace dampbound DAMPBOUND_API {

/// SPEC 7, stated once: the paper's semi-implicit Euler step with uniform c = gamma/m is
/// linearly stable about a state whose M^-1 K has largest eigenvalue lambda_max iff
/// 0 < c dt < 2 and lambda_max dt^2 < 4 - 2 c dt. Every caller uses these three.
/// Whether (lambda_max, c, dt) breaks it (c = 0 is marginal: not unstable).
bool spec7_unstable(double lambda_max, double c, double dt);
/// The damping limit for mass m: gamma < 2 m/dt - m lambda_max dt/2 (may be <= 0: none).
double spec7_gamma_max(double lambda_max, double m, double dt);
/// The undamped step limit: dt < 2/sqrt(lambda_max); inf when lambda_max <= 0.
double spec7_dt_max_undamped(double lambda_max);

/// The exact limits of the paper's semi-implicit Euler step for uniform c = gamma/m
/// (SPEC 7): stable iff 0 < c dt < 2 and lambda dt^2 < 4 - 2 c dt for every mode.
struct LinearLimits {
  double lambda_max = 0;     ///< 1/s^2
  double gamma_max = 0;      ///< gamma < 2 m/dt - m lambda_max dt/2 (may be <= 0: none)
  double dt_max_undamped = 0;  ///< dt < 2/sqrt(lambda_max) at gamma = 0
};

/// Limits for mass m and step dt from lambda_max.
LinearLimits linear_limits(double lambda_max, double m, double dt);

/// Largest stable dt of the semi-implicit step for uniform c = gamma/m: the root of
/// lambda_max dt^2 + 2 c dt = 4, dt = (sqrt(c^2 + 4 lambda_max) - c) / lambda_max (evaluated as
/// 4 / (c + sqrt(c^2 + 4 lambda_max)), which keeps its digits when 4 lambda_max << c^2).
double semi_implicit_dt_max(double lambda_max, double c);

}  // namespace dampbound
