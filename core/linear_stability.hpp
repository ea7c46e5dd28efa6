#pragma once
// Exact linear stability of a step (SPEC 7): linearise the internal forces at a state
// (tangent stiffness K), take the largest eigenvalue lambda_max of M^-1 K with an iterative
// solver (never a dense decomposition of a large mesh), and from it the exact damping
// interval and the largest stable dt.
#include <vector>

#include "core/model.hpp"

namespace dampbound {

/// Largest eigenvalue of M^-1 K, K the tangent stiffness of springs and anchors at positions
/// x (at rest only spring directions and anchors contribute), over the free nodes.
/// Units 1/s^2. Iterative (Lanczos / Spectra); exact to ~1e-10 relative.
double max_stiffness_eigenvalue(const Model& model, const std::vector<Vec3>& x);

/// The exact limits of the paper's semi-implicit Euler step for uniform c = gamma/m
/// (SPEC 7): stable iff 0 < c dt < 2 and lambda dt^2 < 4 - 2 c dt for every mode.
struct LinearLimits {
  double lambda_max = 0;     ///< 1/s^2
  double gamma_max = 0;      ///< gamma < 2 m/dt - m lambda_max dt/2 (may be <= 0: none)
  double dt_max_undamped = 0;  ///< dt < 2/sqrt(lambda_max) at gamma = 0
};

/// Limits for mass m and step dt from lambda_max.
LinearLimits linear_limits(double lambda_max, double m, double dt);

}  // namespace dampbound
