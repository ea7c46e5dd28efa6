#pragma once
// Shared helpers of the core tests.
#include <string>

#include "core/model.hpp"
#include "core/scene.hpp"

namespace dampbound::test {

inline std::string source_path(const std::string& rel) {
  return std::string(DAMPBOUND_SOURCE_DIR) + "/" + rel;
}

/// One free node on a zero-rest-length anchor: the single damped oscillator.
inline Model single_oscillator(const Params& p) {
  Model m;
  add_node(m, Vec3::Zero());
  m.anchor_scale[0] = 1;
  set_params(m, p);
  return m;
}

}  // namespace dampbound::test
