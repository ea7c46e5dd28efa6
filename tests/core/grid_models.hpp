#pragma once
// Small models shared by the tests of the tangent stiffness and of the analyses over it.
#include <vector>

#include "dampbound/run/scene.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound::test {

/// An nx x nz grid of the paper's kind, spacing 0.57, compiled with p.
inline Model grid_model(int nx, int nz, const Params& p) {
  GridSpec g;
  g.nx = nx;
  g.nz = nz;
  g.spacing = 0.57;
  return compile_model(make_grid(g), p);
}

/// m's rest positions shaken by up to `size` (seed 7): stretched and compressed springs.
inline std::vector<Vec3> deformed(const Model& m, double size) {
  std::vector<Vec3> x = m.spec().rest;
  test::shake(x, size, 7);
  return x;
}

}  // namespace dampbound::test
