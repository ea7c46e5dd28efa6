#include "dampbound/physics/bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dampbound {

double lower_bound(double m, double kappa) { return 2.0 * std::sqrt(m * kappa); }

double upper_bound(const Vec3& v, const Vec3& force, double m, double dt) {
  const double speed = v.norm();
  if (speed == 0) return std::numeric_limits<double>::infinity();
  return (v * (m / dt) + force).norm() / speed;
}

const char* to_string(NodeStatus s) {
  switch (s) {
    case NodeStatus::within: return "within";
    case NodeStatus::clamped: return "clamped";
    case NodeStatus::violating: return "violating";
    case NodeStatus::unstabilisable: return "unstabilisable";
    case NodeStatus::fixed: return "fixed";
  }
  return "?";
}

DampingChoice effective_damping(DampingPolicy policy, double gamma, double lo, double hi,
                                double factor, double safe) {
  DampingChoice c;
  c.unstabilisable = lo > hi;
  switch (policy) {
    case DampingPolicy::fixed: c.gamma = gamma; break;
    case DampingPolicy::clamp: c.gamma = c.unstabilisable ? hi : std::clamp(gamma, lo, hi); break;
    case DampingPolicy::upper: c.gamma = std::isinf(hi) ? 0.0 : factor * hi; break;
    case DampingPolicy::lower: c.gamma = lo; break;
    case DampingPolicy::safe:
      c.gamma = lo > safe ? std::max(safe, 0.0) : std::clamp(gamma, lo, safe);
      break;
  }
  c.unguaranteed = lo > safe;
  c.violating = c.gamma < lo || c.gamma > hi;
  if (c.unstabilisable)
    c.status = NodeStatus::unstabilisable;
  else if (c.violating)
    c.status = NodeStatus::violating;
  else if (c.gamma != gamma)
    c.status = NodeStatus::clamped;
  else
    c.status = NodeStatus::within;
  return c;
}

}  // namespace dampbound
