#pragma once
// The two IEEE values core's limits are spoken in, defined once: +inf ("no limit", a node with
// no spring) and NaN ("not computed"). Private to core (sources, not public headers).
#include <limits>

namespace dampbound {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace dampbound
