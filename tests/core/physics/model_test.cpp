// compile_model: every per-node and per-spring value of SPEC 1 and 3 from a spec and the
// uniform parameters; the spec edits (add_node, add_spring, without_springs) a cut uses.
#include "dampbound/physics/model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dampbound {
namespace {

/// Three nodes in a row, 0 - 1 - 2, the second spring three times stiffer; node 0 anchored
/// (scale 2), node 1 twice as heavy and half as damped, node 2 fixed.
ModelSpec three_in_a_row() {
  ModelSpec s;
  add_node(s, Vec3(0, 0, 0));
  add_node(s, Vec3(3, 4, 0));
  add_node(s, Vec3(3, 4, 2));
  s.anchor_scale[0] = 2;
  s.mass_scale[1] = 2;
  s.gamma_scale[1] = 0.5;
  s.fixed[2] = 1;
  add_spring(s, 0, 1);
  add_spring(s, 1, 2, 3);
  return s;
}

Params some_params() {
  Params p;
  p.m = 0.01;
  p.kappa = 0.2;
  p.gamma = 0.03;
  return p;
}

/// Every value compile_model derives from the params, equal in `a` and `b`.
void expect_same_parameter_values(const Model& a, const Model& b) {
  EXPECT_EQ(a.mass, b.mass);
  EXPECT_EQ(a.gamma, b.gamma);
  EXPECT_EQ(a.anchor_kappa, b.anchor_kappa);
  EXPECT_EQ(a.spring_kappa, b.spring_kappa);
  EXPECT_EQ(a.spring_weight, b.spring_weight);
  EXPECT_EQ(a.node_kappa, b.node_kappa);
  EXPECT_EQ(a.lower_bound, b.lower_bound);
}

TEST(ModelSpec, AddNodeAndSpringGiveUnitScalesAndTheRestDistance) {
  const ModelSpec s = three_in_a_row();
  ASSERT_EQ(s.node_count(), 3);
  ASSERT_EQ(s.spring_count(), 2);
  EXPECT_EQ(s.anchor_count(), 1);
  EXPECT_EQ(s.mass_scale[0], 1.0);
  EXPECT_EQ(s.external_force[1], Vec3::Zero());
  EXPECT_DOUBLE_EQ(s.springs[0].rest_length, 5.0);  // |(3, 4, 0)|
  EXPECT_DOUBLE_EQ(s.springs[1].rest_length, 2.0);
  EXPECT_EQ(s.springs[1].kappa_scale, 3.0);
}

TEST(CompileModel, FillsEveryDerivedArrayWithSpec3sValues) {
  const Params p = some_params();
  const Model m = compile_model(three_in_a_row(), p);
  EXPECT_EQ(m.mass, (std::vector<double>{0.01, 0.02, 0.01}));
  EXPECT_EQ(m.gamma, (std::vector<double>{0.03, 0.015, 0.03}));
  EXPECT_EQ(m.anchor_kappa, (std::vector<double>{0.4, 0.0, 0.0}));
  ASSERT_EQ(m.spring_kappa.size(), 2u);
  EXPECT_DOUBLE_EQ(m.spring_kappa[0], 0.2);
  EXPECT_DOUBLE_EQ(m.spring_kappa[1], 0.6000000000000001);  // 0.2 * 3 in doubles
  // kappa_i = the largest stiffness at i: the anchor (0.4) beats the spring (0.2) at node 0.
  EXPECT_DOUBLE_EQ(m.node_kappa[0], 0.4);
  EXPECT_DOUBLE_EQ(m.node_kappa[1], m.spring_kappa[1]);
  EXPECT_DOUBLE_EQ(m.node_kappa[2], m.spring_kappa[1]);
  for (size_t i = 0; i < 3; ++i)
    EXPECT_DOUBLE_EQ(m.lower_bound[i], 2 * std::sqrt(m.mass[i] * m.node_kappa[i])) << i;
  // Each spring's weight in A = M^-1/2 K M^-1/2, the bits SPEC 9's row sums computed inline.
  ASSERT_EQ(m.spring_weight.size(), 2u);
  EXPECT_EQ(m.spring_weight[0], 1.0 / std::sqrt(m.mass[0] * m.mass[1]));
  EXPECT_EQ(m.spring_weight[1], 1.0 / std::sqrt(m.mass[1] * m.mass[2]));
  // The spec travels with it unchanged.
  EXPECT_EQ(m.spec().rest[1], Vec3(3, 4, 0));
  EXPECT_EQ(m.spec().fixed[2], 1);
}

TEST(CompileModel, ALonelyNodeHasNoStiffnessAndNoLowerBound) {
  ModelSpec s;
  add_node(s, Vec3::Zero());
  const Model m = compile_model(s, some_params());
  EXPECT_EQ(m.node_kappa[0], 0.0);
  EXPECT_EQ(m.lower_bound[0], 0.0);
}

TEST(CompileModel, RecompilingAModelWithOtherParamsIsCompilingItsSpec) {
  const Model a = compile_model(three_in_a_row(), some_params());
  Params q = some_params();
  q.kappa = 0.5;
  q.m = 0.3;
  const Model b = compile_model(a, q);
  expect_same_parameter_values(b, compile_model(three_in_a_row(), q));
  EXPECT_NE(b.lower_bound, a.lower_bound);
}

TEST(Reparameterise, InPlaceGivesTheValuesOfCompilingTheSpecAndKeepsTheIncidence) {
  Params q = some_params();
  q.kappa = 0.5;
  q.m = 0.3;
  q.gamma = 0.07;
  Model a = compile_model(three_in_a_row(), q);
  const std::vector<int> offsets = a.incident_offset, incident = a.incident;
  // Down to a smaller kappa: every node's kappa_i must fall with it, not keep the old maximum.
  const Params p = some_params();
  reparameterise(a, p);
  const Model c = compile_model(three_in_a_row(), p);
  expect_same_parameter_values(a, c);
  EXPECT_DOUBLE_EQ(a.node_kappa[1], 0.6000000000000001);  // 0.2 * 3, not 0.5 * 3
  EXPECT_EQ(a.incident_offset, offsets);
  EXPECT_EQ(a.incident, incident);
  EXPECT_EQ(a.incident, c.incident);
}

TEST(WithoutSprings, ACutRemovesItsSpringsAndTheBoundsFollowOnCompile) {
  const Params p = some_params();
  const ModelSpec s = three_in_a_row();
  // Duplicates and indices out of range are ignored; the order of the rest is kept.
  const ModelSpec cut = without_springs(s, {1, 1, 7, -1});
  ASSERT_EQ(cut.spring_count(), 1);
  EXPECT_EQ(cut.springs[0].j, 1);
  const Model m = compile_model(cut, p);
  EXPECT_DOUBLE_EQ(m.node_kappa[1], 0.2);  // the stiff spring is gone
  EXPECT_EQ(m.node_kappa[2], 0.0);
  EXPECT_DOUBLE_EQ(m.lower_bound[1], 2 * std::sqrt(0.02 * 0.2));
  EXPECT_EQ(without_springs(s, {}).spring_count(), 2);
  EXPECT_EQ(without_springs(s, {0, 1}).spring_count(), 0);
}

TEST(RestState, StartsAtRestWithZeroVelocity) {
  const ModelSpec s = three_in_a_row();
  const State st = rest_state(s);
  EXPECT_EQ(st.x, s.rest);
  for (const Vec3& v : st.v) EXPECT_EQ(v, Vec3::Zero());
  EXPECT_EQ(st.time, 0.0);
  EXPECT_EQ(st.iteration, 0);
  EXPECT_EQ(displacement(s, st, 1), 0.0);
}

}  // namespace
}  // namespace dampbound
