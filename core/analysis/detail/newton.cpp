#include "core/analysis/detail/newton.hpp"

#include <cmath>
#include <limits>
#include <tuple>

namespace dampbound::detail {

double newton_step(double t, double value, double slope) {
  return slope > 0 ? t - value / slope : std::numeric_limits<double>::quiet_NaN();
}

double newton_from_right(const std::function<std::pair<double, double>(double)>& g, double t,
                         std::optional<std::pair<double, double>> earlier) {
  double previous_t = 0, previous_slope = 0;
  if (earlier) std::tie(previous_t, previous_slope) = *earlier;
  for (int k = 0; k < 100; ++k) {
    const auto [value, slope] = g(t);
    if (!(slope > 0)) break;
    const double next = t - value / slope;
    if (!(next > 0)) return 0;
    const double step = std::abs(next - t);
    if (step <= 1e-13 * t) return next;
    if (k > 0 || earlier) {
      const double curvature = std::abs((slope - previous_slope) / (t - previous_t)) / (2 * slope);
      if (10 * curvature * step * step <= 1e-13 * t) return next;
    }
    previous_t = t;
    previous_slope = slope;
    t = next;
  }
  return t;
}

}  // namespace dampbound::detail
