#pragma once
// Shared helpers of the core tests.
#include <string>
#include <utility>

#include "core/model.hpp"
#include "core/scene.hpp"

namespace dampbound::test {

inline std::string source_path(const std::string& rel) {
  return std::string(DAMPBOUND_SOURCE_DIR) + "/" + rel;
}

/// One free node on a zero-rest-length anchor: the single damped oscillator.
inline Model single_oscillator(const Params& p) {
  ModelSpec m;
  add_node(m, Vec3::Zero());
  m.anchor_scale[0] = 1;
  return compile_model(std::move(m), p);
}

}  // namespace dampbound::test
