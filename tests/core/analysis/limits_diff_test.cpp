// diff's limits and what changed them: the dt limit against a bisection on the dense
// amplification matrix, the baseline JSON read back bit for bit, and a pair of scenes where one
// stiff spring halves the step, with the new scene's nodes renumbered.
#include "core/analysis/limits_diff.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "dampbound/physics/error.hpp"
#include "tests/core/dense_step.hpp"

namespace dampbound {
namespace {

/// A 5 x 5 anchored plane (spacing 0.57, diagonals), node 0 fixed; `reverse` numbers the nodes
/// backwards (same geometry and springs).
SceneSpec plane(bool reverse, double stiff_scale) {
  SceneSpec s;
  s.name = reverse ? "reversed" : "plane";
  const int n = 5, count = n * n;
  const auto id = [&](int a, int b) { return reverse ? count - 1 - (a * n + b) : a * n + b; };
  for (int k = 0; k < count; ++k) add_node(s.model, Vec3::Zero());
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const size_t i = static_cast<size_t>(id(a, b));
      s.model.rest[i] = Vec3(a * 0.57, 0, b * 0.57);
      s.model.anchor_scale[i] = 1;
    }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      if (a + 1 < n) add_spring(s.model, id(a, b), id(a + 1, b));
      if (b + 1 < n) add_spring(s.model, id(a, b), id(a, b + 1), a == 2 && b == 2 ? stiff_scale : 1.0);
      if (a + 1 < n && b + 1 < n) add_spring(s.model, id(a, b), id(a + 1, b + 1));
    }
  s.model.fixed[static_cast<size_t>(id(0, 0))] = 1;
  s.params.m = s.params.kappa = 0.001;
  s.params.gamma = 0.002;
  s.params.dt = 0.05;
  return s;
}

TEST(LimitsDiff, DtLimitMatchesTheDenseAmplificationMatrix) {
  const SceneSpec s = plane(false, 16);
  const LimitsSnapshot snap = limits_snapshot(s, s.params);
  const Model model = compile_model(s.model, s.params);
  double lo = 0.5 * snap.dt_limit, hi = 1.5 * snap.dt_limit;
  ASSERT_LT(test::dense_step_radius(model, lo), 1);
  ASSERT_GT(test::dense_step_radius(model, hi), 1);
  for (int k = 0; k < 50; ++k) {
    const double mid = 0.5 * (lo + hi);
    (test::dense_step_radius(model, mid) < 1 ? lo : hi) = mid;
  }
  EXPECT_NEAR(snap.dt_limit, lo, 1e-7 * lo);
  // The limiting mode sits at the stiff spring's ends (nodes 12 and 13).
  ASSERT_GE(snap.mode_nodes.size(), 2u);
  std::vector<int> top(snap.mode_nodes.begin(), snap.mode_nodes.begin() + 2);
  std::sort(top.begin(), top.end());
  EXPECT_EQ(top, (std::vector<int>{12, 13}));
  EXPECT_EQ(limit_substeps(1.0, snap.dt_limit), static_cast<int>(std::floor(1.0 / snap.dt_limit)) + 1);
}

TEST(LimitsDiff, BaselineJsonReadsBackBitForBit) {
  const SceneSpec s = plane(false, 4);
  const LimitsSnapshot a = limits_snapshot(s, s.params);
  std::ostringstream out;
  write_limits_json(out, a);
  const LimitsSnapshot b = read_limits_json(out.str(), "base.json");
  EXPECT_EQ(b.scene, a.scene);
  EXPECT_EQ(b.dt_limit, a.dt_limit);
  EXPECT_EQ(b.gamma_hi, a.gamma_hi);
  EXPECT_EQ(b.dt_safe, a.dt_safe);
  EXPECT_EQ(b.params.gamma, a.params.gamma);
  EXPECT_EQ(b.rest, a.rest);
  EXPECT_EQ(b.node_dt_safe, a.node_dt_safe);
  EXPECT_EQ(b.spring_kappa, a.spring_kappa);
  EXPECT_EQ(b.mode_nodes, a.mode_nodes);
  EXPECT_EQ(b.worst.size(), a.worst.size());
  EXPECT_EQ(b.fixed, a.fixed);
  const LimitsDiff same = diff_limits(a, b);
  EXPECT_EQ(same.drop, 0);
  EXPECT_TRUE(same.changes.empty());
  EXPECT_THROW(read_limits_json("{\"format\":\"other\"}", "x.json"), InputError);
  EXPECT_THROW(read_limits_json(out.str().substr(0, 100), "x.json"), InputError);
}

TEST(LimitsDiff, OneStiffSpringIsNamedInTheRenumberedScene) {
  const SceneSpec before = plane(false, 1), after = plane(true, 16);
  const LimitsSnapshot o = limits_snapshot(before, before.params),
                       n = limits_snapshot(after, after.params);
  const LimitsDiff d = diff_limits(o, n);
  EXPECT_EQ(d.matched_nodes, 25);
  EXPECT_TRUE(d.renumbered);
  EXPECT_GT(d.drop, 0.4);  // about half the step
  ASSERT_FALSE(d.changes.empty());
  // Old nodes 12-13 are new nodes 12 and 11 (24 - i).
  EXPECT_EQ(d.changes[0].what.rfind("spring 12-11 ", 0), 0u) << d.changes[0].what;
  EXPECT_NE(d.changes[0].what.find("kappa x16"), std::string::npos) << d.changes[0].what;
  EXPECT_GT(d.changes[0].weight, 0.3);
  ASSERT_FALSE(d.falls.empty());
  EXPECT_TRUE(d.falls[0].node == 12 || d.falls[0].node == 11);
  EXPECT_TRUE(d.parameters.empty());
  EXPECT_EQ(d.changed_springs, 1);
  EXPECT_EQ(d.changed_nodes, 0);
}

}  // namespace
}  // namespace dampbound
