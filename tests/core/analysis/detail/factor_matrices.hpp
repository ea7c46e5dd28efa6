#pragma once
// Mesh matrices A = M^-1/2 K M^-1/2 whose factorisations the tests of the Cholesky helpers
// (cholesky_rounding, supernodal_solve) take apart: a plane shaken out of its rest shape and
// a tetrahedral block at rest.
#include <vector>

#include "bench/bench_meshes.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound::test {

inline SparseMatrix deformed_plane(int n) {
  const Model m = compile_model(make_grid(GridSpec{n, n, 0.57, true, true}), Params{});
  std::vector<Vec3> x = m.spec().rest;
  test::shake(x, 0.2, 11);
  return mass_weighted(m, tangent_stiffness(m, x));
}

inline SparseMatrix block(int n) {
  const Model m = compile_model(bench::tet_block(n, n, n), Params{});
  return mass_weighted(m, tangent_stiffness(m, m.spec().rest));
}

}  // namespace dampbound::test
