#pragma once
// Big meshes for the benchmarks, built in code: the paper's plane at any size (SPEC 5's
// geometry, anchors at every node) and a structured tetrahedral block.
#include "dampbound/run/scene.hpp"

namespace dampbound::bench {

/// An n x n paper plane (SPEC 5: spacing 0.57 cm, one diagonal per cell, an anchor per node):
/// n^2 nodes, 3 n^2 - 4 n + 1 springs.
inline ModelSpec plane(int n) { return make_grid(GridSpec{n, n, 0.57, true, true}); }

/// A block of nx x ny x nz nodes, spacing h = 0.57 cm, each cube cut into the 6 tetrahedra of
/// Kuhn's triangulation: the tetrahedra's edges are the springs from every node (a, b, c) to
/// (a, b, c) + e for the 7 non-zero e in {0, 1}^3 (7 springs per interior node). The bottom
/// layer (b = 0) is fixed, no anchors: a slab of tissue resting on a support.
inline ModelSpec tet_block(int nx, int ny, int nz) {
  ModelSpec model;
  const double h = 0.57;
  auto index = [&](int a, int b, int c) { return (a * ny + b) * nz + c; };
  for (int a = 0; a < nx; ++a)
    for (int b = 0; b < ny; ++b)
      for (int c = 0; c < nz; ++c) {
        add_node(model, Vec3(a * h, b * h, c * h));
        if (b == 0) model.fixed.back() = 1;
      }
  for (int a = 0; a < nx; ++a)
    for (int b = 0; b < ny; ++b)
      for (int c = 0; c < nz; ++c)
        for (int e = 1; e < 8; ++e) {
          const int a2 = a + (e & 1), b2 = b + ((e >> 1) & 1), c2 = c + ((e >> 2) & 1);
          if (a2 < nx && b2 < ny && c2 < nz) add_spring(model, index(a, b, c), index(a2, b2, c2));
        }
  return model;
}

/// Moves every free node of `s` by up to 0.005 cm per axis (a fixed LCG, the same on every
/// run), so the springs are stretched and compressed as in a running simulation.
inline void shake(const Model& model, State& s) {
  unsigned seed = 1;
  for (size_t i = 0; i < s.x.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    for (int k = 0; k < 3; ++k) {
      seed = seed * 1103515245u + 12345u;
      s.x[i][k] += 0.01 * (static_cast<double>((seed >> 8) & 0xffffu) / 65535.0 - 0.5);
    }
  }
}

}  // namespace dampbound::bench
