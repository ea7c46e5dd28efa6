#include "dampbound/physics/closed_forms.hpp"

#include <cmath>
#include <limits>

namespace dampbound {

bool spec7_unstable(double lambda_max, double c, double dt) {
  const double c_dt = c * dt;
  return !(c_dt < 2) || !(lambda_max * dt * dt < 4 - 2 * c_dt);
}

double spec7_gamma_max(double lambda_max, double m, double dt) {
  // lambda dt^2 < 4 - 2 c dt, c = gamma/m  =>  gamma < 2m/dt - m lambda dt / 2.
  return 2.0 * m / dt - m * lambda_max * dt / 2.0;
}

double spec7_dt_max_undamped(double lambda_max) {
  return lambda_max > 0 ? 2.0 / std::sqrt(lambda_max) : std::numeric_limits<double>::infinity();
}

LinearLimits linear_limits(double lambda_max, double m, double dt) {
  LinearLimits l;
  l.lambda_max = lambda_max;
  l.gamma_max = spec7_gamma_max(lambda_max, m, dt);
  l.dt_max_undamped = spec7_dt_max_undamped(lambda_max);
  return l;
}

double semi_implicit_dt_max(double lambda_max, double c) {
  // lambda dt^2 + 2 c dt - 4 = 0, the positive root; dt < 2/c when lambda = 0.
  // Written as 4 / (c + sqrt(c^2 + 4 lambda)): (sqrt(c^2 + 4 lambda) - c) / lambda loses every
  // digit to cancellation where 4 lambda is far below c^2 (a heavily damped or nearly free
  // node: it rounds to 0), and hypot keeps c^2 from overflowing.
  if (!(lambda_max > 0)) return c > 0 ? 2.0 / c : std::numeric_limits<double>::infinity();
  return 4.0 / (c + std::hypot(c, 2.0 * std::sqrt(lambda_max)));
}

}  // namespace dampbound
