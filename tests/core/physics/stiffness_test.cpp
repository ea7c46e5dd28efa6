// The tangent stiffness K = -dF/dx (include/dampbound/physics/stiffness.hpp): the force Jacobian, assembled in the
// same bits however it is built.
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
#include "dampbound/physics/stiffness.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/physics/detail/spring_block.hpp"
#include "dampbound/physics/forces.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/grid_models.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

using test::deformed;
using test::grid_model;

TEST(TangentStiffness, IsMinusTheForceJacobian) {
  Params p;
  p.kappa = 0.3;
  ModelSpec spec = grid_model(3, 3, p).spec();
  spec.fixed[4] = 1;  // the middle node: its block must be absent
  const Model m = compile_model(spec, p);
  const std::vector<Vec3> x = deformed(m, 0.2);  // stretched and compressed springs
  const SparseMatrix K = tangent_stiffness(m, x);
  const std::vector<int> block = free_blocks(m);
  ASSERT_EQ(K.rows(), 3 * 8);
  const double eps = 1e-6;
  std::vector<Vec3> fp, fm;
  double worst = 0;
  for (size_t j = 0; j < x.size(); ++j) {
    if (block[j] < 0) continue;
    for (int c = 0; c < 3; ++c) {
      std::vector<Vec3> xp = x, xm = x;
      xp[j][c] += eps;
      xm[j][c] -= eps;
      internal_forces(m, xp, fp);
      internal_forces(m, xm, fm);
      for (size_t i = 0; i < x.size(); ++i) {
        if (block[i] < 0) continue;
        for (int r = 0; r < 3; ++r) {
          const double fd = -(fp[i][r] - fm[i][r]) / (2 * eps);
          worst = std::max(worst, std::abs(fd - K.coeff(3 * block[i] + r, 3 * block[j] + c)));
        }
      }
    }
  }
  EXPECT_LT(worst, 1e-7);
  EXPECT_LT((SparseMatrix(K.transpose()) - K).norm(), 1e-14);
}

/// The tangent stiffness as a triplet list summed by setFromTriplets (anchors first, then each
/// spring's four blocks in index order, zero terms skipped): what tangent_stiffness assembled
/// before it wrote compressed storage directly, kept as the reference for its bits.
SparseMatrix tangent_stiffness_by_triplets(const Model& model, const std::vector<Vec3>& x,
                                           bool clamp_compression) {
  int nfree = 0;
  const std::vector<int> block = free_blocks(model, &nfree);
  std::vector<Eigen::Triplet<double>> t;
  auto add = [&](int bi, int bj, const double* b, double sign) {
    if (bi < 0 || bj < 0) return;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (b[sym3(r, c)] != 0) t.emplace_back(3 * bi + r, 3 * bj + c, sign * b[sym3(r, c)]);
  };
  for (size_t i = 0; i < model.spec().rest.size(); ++i)
    if (block[i] >= 0 && model.anchor_kappa[i] > 0)
      for (int r = 0; r < 3; ++r) t.emplace_back(3 * block[i] + r, 3 * block[i] + r, model.anchor_kappa[i]);
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    const Spring& s = model.spec().springs[k];
    const Vec3 delta = x[static_cast<size_t>(s.j)] - x[static_cast<size_t>(s.i)];
    const double l = delta.norm();
    if (!(l > 0)) continue;
    const Vec3 d = delta / l;
    const double ratio = s.rest_length / l;
    double tension = 1.0 - ratio;
    if (clamp_compression) tension = std::max(0.0, tension);
    double b[6];
    spring_tangent_block(model.spring_kappa[k], tension, ratio, d.data(), b);
    const int bi = block[static_cast<size_t>(s.i)], bj = block[static_cast<size_t>(s.j)];
    add(bi, bi, b, 1);
    add(bj, bj, b, 1);
    add(bi, bj, b, -1);
    add(bj, bi, b, -1);
  }
  SparseMatrix K(3 * nfree, 3 * nfree);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

void expect_same_bits(const SparseMatrix& a, const SparseMatrix& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  ASSERT_TRUE(a.isCompressed() && b.isCompressed());
  for (Eigen::Index k = 0; k <= a.outerSize(); ++k)
    ASSERT_EQ(a.outerIndexPtr()[k], b.outerIndexPtr()[k]) << "column " << k;
  for (Eigen::Index k = 0; k < a.nonZeros(); ++k) {
    ASSERT_EQ(a.innerIndexPtr()[k], b.innerIndexPtr()[k]) << "entry " << k;
    ASSERT_EQ(std::memcmp(a.valuePtr() + k, b.valuePtr() + k, sizeof(double)), 0)
        << "entry " << k << ": " << a.valuePtr()[k] << " vs " << b.valuePtr()[k];
  }
}

TEST(TangentStiffness, SameBitsAsTheTripletSum) {
  // A grid at rest (exact zeros: no out-of-plane entries), then deformed with fixed nodes,
  // uneven anchors (none at some nodes), a doubled spring, a spring of zero length,
  // compressed springs and a spring to itself; with and without clamping compression.
  Params p;
  p.kappa = 0.003;
  GridSpec g;
  g.nx = 7;
  g.nz = 6;
  g.spacing = 0.57;
  g.diagonals = true;
  g.anchors = true;
  ModelSpec spec = make_grid(g);
  {
    const Model at_rest = compile_model(spec, p);
    expect_same_bits(tangent_stiffness(at_rest, at_rest.spec().rest),
                     tangent_stiffness_by_triplets(at_rest, at_rest.spec().rest, false));
  }
  spec.fixed[0] = spec.fixed[5] = 1;
  for (size_t i = 0; i < spec.anchor_scale.size(); ++i) spec.anchor_scale[i] = (i % 3 == 0) ? 0 : 0.5 * static_cast<double>(i % 4);
  add_spring(spec, 8, 9, 2.0);   // the pair (8, 9) now has two springs
  add_spring(spec, 12, 12, 1.0); // a spring to itself: no direction
  add_spring(spec, 20, 27, 0.7);
  add_spring(spec, 3, 4, 1.0);
  Model model = compile_model(spec, p);
  std::vector<Vec3> x = model.spec().rest;
  test::shake(x, 0.3, 11);
  x[4] = x[3];  // the spring (3, 4) has zero length
  int compressed = 0;
  for (const Spring& s : model.spec().springs)
    compressed += (x[static_cast<size_t>(s.j)] - x[static_cast<size_t>(s.i)]).norm() < s.rest_length;
  ASSERT_GT(compressed, 0);
  for (bool clamp : {false, true})
    expect_same_bits(tangent_stiffness(model, x, clamp), tangent_stiffness_by_triplets(model, x, clamp));
  // The deformed model at rest: the doubled and the added springs, still exact zeros.
  expect_same_bits(tangent_stiffness(model, model.spec().rest),
                   tangent_stiffness_by_triplets(model, model.spec().rest, false));
}

TEST(TangentStiffness, SameBitsOnAnyThreadCount) {
  // Threads take the springs and the nodes in ranges of at least 16384: a 230 x 230 grid
  // (52 900 nodes) splits into three. Deformed, with fixed nodes and nodes without anchors.
  Params p;
  p.kappa = 0.003;
  ModelSpec spec = make_grid(GridSpec{230, 230, 0.57, true, true});
  for (size_t i = 0; i < spec.fixed.size(); i += 997) spec.fixed[i] = 1;
  for (size_t i = 0; i < spec.anchor_scale.size(); i += 5) spec.anchor_scale[i] = 0;
  const Model model = compile_model(spec, p);
  std::vector<Vec3> x = model.spec().rest;
  test::shake(x, 0.2, 5);
  for (bool clamp : {false, true}) {
    const SparseMatrix one = tangent_stiffness(model, x, clamp, 1);
    for (int threads : {2, 3}) {
      SCOPED_TRACE(testing::Message() << threads << " threads, clamp " << clamp);
      const SparseMatrix many = tangent_stiffness(model, x, clamp, threads);
      expect_same_bits(many, one);
      expect_same_bits(mass_weighted(model, many, threads), mass_weighted(model, one, 1));
    }
  }
}

}  // namespace
}  // namespace dampbound
