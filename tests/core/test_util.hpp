#pragma once
// Shared helpers of the core tests.
#include <functional>
#include <string>
#include <utility>

#include "core/error.hpp"

#include "core/model.hpp"
#include "core/scene.hpp"

namespace dampbound::test {

inline std::string source_path(const std::string& rel) {
  return std::string(DAMPBOUND_SOURCE_DIR) + "/" + rel;
}

/// The message of the InputError that `f` throws, or "" when it throws none.
inline std::string input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// One free node on a zero-rest-length anchor: the single damped oscillator.
inline Model single_oscillator(const Params& p) {
  ModelSpec m;
  add_node(m, Vec3::Zero());
  m.anchor_scale[0] = 1;
  return compile_model(std::move(m), p);
}

}  // namespace dampbound::test
