// SPEC 10's generalised safe bound (core/physics/safe_bound_damped.cpp) by hand on one free node, and
// the step's one-pass gammas against the rows.
#include <gtest/gtest.h>

#include <cmath>

#include "core/physics/safe_bound.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {
namespace {

/// Node 0 free and anchored, node 1 fixed, one spring along x at rest: K_00 = kappa P +
/// kappa_a I with P = e_x e_x^T, C'_00 = alpha m I + beta K_00 + kd P + kd_a I, and no
/// off-diagonal entry (the neighbour is fixed, P is diagonal).
Model one_free_node(const Params& p) {
  ModelSpec s;
  add_node(s, Vec3(0, 0, 0));
  add_node(s, Vec3(0.5, 0, 0));
  s.anchor_scale[0] = 1;
  s.fixed[1] = 1;
  add_spring(s, 0, 1, 2.0);
  return compile_model(s, p);
}

TEST(SafeBoundDamped, OneFreeNodeByHand) {
  Params p;
  p.m = 0.5;
  p.kappa = 3.0;
  p.dt = 0.05;
  p.kd = 0.4;
  p.rayleigh_mass = 0.2;
  p.rayleigh_stiffness = 0.01;
  const Model model = one_free_node(p);
  ASSERT_TRUE(model.spring_damping);
  const double m = model.mass[0], k = model.spring_kappa[0], ka = model.anchor_kappa[0];
  const double kd = model.spring_kd[0], kda = model.anchor_kd[0];
  // Row x carries the spring, rows y and z only the anchor: x is the tightest.
  const double a = (k + ka) / m;
  const double c = p.rayleigh_mass + (p.rayleigh_stiffness * (k + ka) + kd + kda) / m;
  const double margin = 4 - 2 * p.dt * c - p.dt * p.dt * a;
  const DampedSafeRows rows(model, model.spec().rest);
  EXPECT_NEAR(rows.gamma_safe(0, p.dt), m / (2 * p.dt) * margin, 1e-12);
  // dt_safe at gamma: the positive root of a t^2 + 2 (gamma/m + c) t = 4.
  const double gamma = 0.3, P = 2 * (gamma / m + c);
  const double root = (-P + std::sqrt(P * P + 16 * a)) / (2 * a);
  EXPECT_NEAR(rows.dt_safe(0, gamma), root, 1e-12);
  std::vector<double> g;
  damped_safe_gammas(model, model.spec().rest, p.dt, g);
  EXPECT_EQ(g[0], rows.gamma_safe(0, p.dt));
  EXPECT_TRUE(std::isinf(g[1]));  // a fixed node has no bound
}

TEST(SafeBoundDamped, StretchedSpringsGiveOffDiagonalsBothWaysAgree) {
  // A chain of free nodes, stretched and bent: the one-pass gammas of step() equal the rows'.
  Params p;
  p.kd = 0.003;
  p.rayleigh_mass = 0.2;
  p.rayleigh_stiffness = 0.01;
  ModelSpec s;
  for (int i = 0; i < 5; ++i) {
    add_node(s, Vec3(0.57 * i, 0, 0));
    s.anchor_scale[static_cast<size_t>(i)] = 1;
  }
  for (int i = 0; i + 1 < 5; ++i) add_spring(s, i, i + 1, 1.0 + i);
  const Model model = compile_model(s, p);
  std::vector<Vec3> x = model.spec().rest;
  x[2] += Vec3(0.1, 0.2, -0.05);
  x[4] += Vec3(0.3, 0, 0);
  std::vector<double> g;
  damped_safe_gammas(model, x, p.dt, g);
  const DampedSafeRows rows(model, x);
  for (size_t i = 0; i < g.size(); ++i) EXPECT_EQ(g[i], rows.gamma_safe(static_cast<int>(i), p.dt));
  // Stretching lowers the bound of the bent node below its value at rest.
  const DampedSafeRows at_rest(model, model.spec().rest);
  EXPECT_LT(rows.gamma_safe(2, p.dt), at_rest.gamma_safe(2, p.dt));
}

}  // namespace
}  // namespace dampbound
