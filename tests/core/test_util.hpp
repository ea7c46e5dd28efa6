#pragma once
// Shared helpers of the core tests.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "dampbound/physics/error.hpp"

#include "dampbound/physics/model.hpp"
#include "dampbound/run/scene.hpp"

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

/// A k x k x k lattice of nodes `spacing` apart, node (a, b, c) at index (a k + b) k + c,
/// with springs to its 7 forward neighbours (axes, face and body diagonals; kappa scale
/// 1 + e % 3 for direction e). `node(spec, i, a, b, c)` sets node i's scales and flags.
inline ModelSpec cube_lattice(int k, double spacing,
                              const std::function<void(ModelSpec&, int, int, int, int)>& node) {
  ModelSpec m;
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b)
      for (int c = 0; c < k; ++c) node(m, add_node(m, Vec3(a, b, c) * spacing), a, b, c);
  auto at = [&](int a, int b, int c) { return (a * k + b) * k + c; };
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b)
      for (int c = 0; c < k; ++c)
        for (int e = 1; e < 8; ++e) {
          const int a2 = a + (e & 1), b2 = b + ((e >> 1) & 1), c2 = c + ((e >> 2) & 1);
          if (a2 < k && b2 < k && c2 < k) add_spring(m, at(a, b, c), at(a2, b2, c2), 1 + (e % 3));
        }
  return m;
}

/// Moves every coordinate by a deterministic pseudo-random amount in [-amplitude/2,
/// amplitude/2] (a linear congruential sequence from `seed`).
inline void shake(std::vector<Vec3>& x, double amplitude, unsigned seed) {
  for (Vec3& xi : x)
    for (int d = 0; d < 3; ++d) {
      seed = seed * 1103515245u + 12345u;
      xi[d] += amplitude * (static_cast<double>((seed >> 8) & 0xffffu) / 65535.0 - 0.5);
    }
}

/// One free node on a zero-rest-length anchor: the single damped oscillator.
inline Model single_oscillator(const Params& p) {
  ModelSpec m;
  add_node(m, Vec3::Zero());
  m.anchor_scale[0] = 1;
  return compile_model(std::move(m), p);
}

}  // namespace dampbound::test
