#pragma once
// The paper's damping bounds (eqs. 5, 6), the runtime check (sec. 5) and the damping
// policies (sec. 5, "Dynamic damping"; SPEC 3-4).
#include "dampbound/physics/export.hpp"
#include <cstdint>
#include <limits>

#include "dampbound/physics/model.hpp"

namespace dampbound DAMPBOUND_API {

/// Paper eq. 5: gamma_lo = 2 sqrt(m kappa) (mass unit / s).
double lower_bound(double m, double kappa);

/// Paper eq. 6: gamma_hi = |v m/dt + F| / |v| from the state at t; +infinity when |v| = 0
/// (damping has no effect on the node this step).
double upper_bound(const Vec3& v, const Vec3& force, double m, double dt);

/// What the policy did to a node this step, most severe first.
enum class NodeStatus : std::uint8_t {
  within,          ///< effective gamma in [lo, hi] and equal to the user's gamma
  clamped,         ///< the policy changed gamma, and the result is within [lo, hi]
  violating,       ///< effective gamma outside [lo, hi]
  unstabilisable,  ///< lo > hi: no damping satisfies both bounds (paper sec. 5)
  fixed,           ///< a fixed node: never moves, not judged
};

const char* to_string(NodeStatus s);

/// The effective damping of one node and how it relates to the bounds.
struct DampingChoice {
  double gamma = 0;
  NodeStatus status = NodeStatus::within;
  bool violating = false;       ///< gamma outside [lo, hi] (SPEC 3)
  bool unstabilisable = false;  ///< lo > hi
  bool unguaranteed = false;    ///< lo > gamma_safe: critical damping not guaranteed (SPEC 9)
};

/// SPEC 4: fixed -> gamma; clamp -> clamp(gamma, lo, hi), hi when lo > hi; upper ->
/// factor * hi (0 when hi = inf); lower -> lo. SPEC 9: safe -> clamp(gamma, lo, safe), and
/// max(safe, 0) when lo > safe (stability first; a negative damping would feed energy in).
/// `safe` is gamma_safe_i (safe_bound.hpp), +inf when not computed.
DampingChoice effective_damping(DampingPolicy policy, double gamma, double lo, double hi,
                                double factor,
                                double safe = std::numeric_limits<double>::infinity());

}  // namespace dampbound
