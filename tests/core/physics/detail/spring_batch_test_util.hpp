#pragma once
// The mesh the spring batch's tests share: a shaken 10^3 lattice with diagonals and varied
// masses (so w = 1/sqrt(m_i m_j) varies), springs stretched and compressed, spring 0 of zero
// length and spring 5 with a NaN end.
#include <limits>
#include <vector>

#include "dampbound/physics/model.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound::test {

struct BatchMesh {
  Model model;
  std::vector<Vec3> x;
};

inline BatchMesh batch_mesh() {
  Params p;
  BatchMesh out{compile_model(cube_lattice(10, 1.0,
                                           [](ModelSpec& m, int i, int, int, int) {
                                             m.mass_scale.back() = 1 + (i % 5) * 0.5;
                                           }),
                              p),
                {}};
  out.x = out.model.spec().rest;
  shake(out.x, 0.3, 11);
  const Spring& s0 = out.model.spec().springs[0];
  out.x[static_cast<size_t>(s0.j)] = out.x[static_cast<size_t>(s0.i)];
  out.x[static_cast<size_t>(out.model.spec().springs[5].j)][1] = std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace dampbound::test
