// The internal force of SPEC 1 by hand: a stretched and a compressed spring, an anchor, a
// spring of zero length, and Newton's third law over a random mesh.
#include "dampbound/physics/forces.hpp"

#include <gtest/gtest.h>

#include <random>

namespace dampbound {
namespace {

Params unit_kappa(double kappa) {
  Params p;
  p.kappa = kappa;
  return p;
}

TEST(InternalForces, AStretchedSpringPullsItsEndsTogether) {
  ModelSpec s;
  add_node(s, Vec3(0, 0, 0));
  add_node(s, Vec3(2, 0, 0));
  add_spring(s, 0, 1, 1.5);  // l0 = 2, kappa_ij = 0.3
  const Model m = compile_model(s, unit_kappa(0.2));
  std::vector<Vec3> f;
  // Stretched to l = 5 along (3, 4, 0)/5: |f| = 0.3 (5 - 2) = 0.9 along the spring.
  EXPECT_EQ(internal_forces(m, {Vec3(0, 0, 0), Vec3(3, 4, 0)}, f), 0);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_NEAR(f[0].x(), 0.9 * 0.6, 1e-15);
  EXPECT_NEAR(f[0].y(), 0.9 * 0.8, 1e-15);
  EXPECT_EQ(f[0].z(), 0.0);
  EXPECT_EQ(f[1], -f[0]);
  // Compressed to l = 1: the spring pushes them apart with 0.3 (1 - 2) = -0.3.
  internal_forces(m, {Vec3(0, 0, 0), Vec3(0, 0, 1)}, f);
  EXPECT_NEAR(f[0].z(), -0.3, 1e-15);
  EXPECT_NEAR(f[1].z(), 0.3, 1e-15);
}

TEST(InternalForces, AnAnchorPullsBackToRest) {
  ModelSpec s;
  add_node(s, Vec3(1, 1, 1));
  s.anchor_scale[0] = 4;  // kappa_a = 0.4
  s.external_force[0] = Vec3(9, 9, 9);  // not an internal force: left out
  const Model m = compile_model(s, unit_kappa(0.1));
  std::vector<Vec3> f;
  internal_forces(m, {Vec3(1, 3, 0)}, f);
  EXPECT_NEAR(f[0].x(), 0.0, 1e-15);
  EXPECT_NEAR(f[0].y(), -0.8, 1e-15);
  EXPECT_NEAR(f[0].z(), 0.4, 1e-15);
}

TEST(InternalForces, AZeroLengthSpringIsCountedAndAddsNothing) {
  ModelSpec s;
  add_node(s, Vec3(0, 0, 0));
  add_node(s, Vec3(1, 0, 0));
  add_spring(s, 0, 1);
  const Model m = compile_model(s, unit_kappa(1));
  std::vector<Vec3> f;
  EXPECT_EQ(internal_forces(m, {Vec3(2, 2, 2), Vec3(2, 2, 2)}, f), 1);
  EXPECT_EQ(f[0], Vec3::Zero());
  EXPECT_EQ(f[1], Vec3::Zero());
}

TEST(InternalForces, SpringForcesSumToZero) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ModelSpec s;
  for (int i = 0; i < 12; ++i) add_node(s, Vec3(u(rng), u(rng), u(rng)));
  for (int i = 0; i < 12; ++i)
    for (int j = i + 1; j < 12; j += 3) add_spring(s, i, j, 1 + u(rng) * 0.5);
  const Model m = compile_model(s, unit_kappa(0.7));
  std::vector<Vec3> x = m.spec().rest;
  for (Vec3& q : x) q += 0.3 * Vec3(u(rng), u(rng), u(rng));
  std::vector<Vec3> f;
  internal_forces(m, x, f);
  Vec3 total = Vec3::Zero();
  double scale = 0;
  for (const Vec3& fi : f) total += fi, scale += fi.norm();
  EXPECT_GT(scale, 0.1);
  EXPECT_LT(total.norm(), 1e-14 * scale);
}

}  // namespace
}  // namespace dampbound
