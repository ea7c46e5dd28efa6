#pragma once
// The root of a convex increasing function by Newton's method from the right: the exact
// limits of the paper's step with non-uniform damping rates, the roots in gamma and in dt of
// the symmetric index less 4 (linear_stability_exact.cpp). Each evaluation there is a
// certified lambda_max, two factorisations, so the stop rule saves the one that would only
// confirm convergence.
#include <functional>
#include <optional>
#include <utility>

namespace dampbound::detail {

/// The root of a convex increasing g on (0, t] with g(t) >= 0; `g` returns (g, g'). Every
/// Newton iterate of such a g lies right of the root, whichever side it starts from, so the
/// result is on the side where g >= 0, within rounding. Returns 0 when an iterate would not be
/// positive (g(0+) >= 0). It stops once a step is below 1e-13 of the iterate, or once the step
/// after it would be: Newton's error squares every step, the next step being about
/// g'' / (2 g') times this one squared, with g'' from the last two slopes, and ten times that
/// below 1e-13 of the iterate is taken as converged. `earlier`: the point and slope of an
/// evaluation made before t (the step to t taken by the caller), for the first step's g''.
double newton_from_right(const std::function<std::pair<double, double>(double)>& g, double t,
                         std::optional<std::pair<double, double>> earlier = std::nullopt);

/// One Newton step from t, where g = value with slope `slope`: for a convex increasing g it
/// lands right of the root from either side. NaN where it cannot be taken (slope <= 0).
double newton_step(double t, double value, double slope);

}  // namespace dampbound::detail
