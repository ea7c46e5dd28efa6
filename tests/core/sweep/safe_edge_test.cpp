// The safe bound of SPEC 9 on a sweep: its edges lie on the safe check's boundary and inside
// the exact linear limit of SPEC 7; the confusion table counts what it should.
#include "core/sweep/safe_edge.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/sweep/summary.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

TEST(SweepSafeEdge, UnitBoundHasOneEntryPerFreeNode) {
  const SafeUnit u = unit_safe_bound(test::shipped_scene("two-node"));
  ASSERT_FALSE(u.row_sum.empty());
  EXPECT_EQ(u.mass_scale.size(), u.row_sum.size());
  EXPECT_EQ(u.gamma_scale.size(), u.row_sum.size());
  for (double r : u.row_sum) EXPECT_GT(r, 0);
}

TEST(SweepSafeEdge, EdgesAreTheSafeChecksBoundaryAndInsideTheExactLimit) {
  for (const char* name : {"two-node", "paper-plane"}) {
    SCOPED_TRACE(name);
    const SceneSpec scene = test::shipped_scene(name);
    const SafeUnit u = unit_safe_bound(scene);
    const double lambda = unit_stiffness_eigenvalue(scene);
    const double m = 0.001, kappa = 0.001, dt = 0.05;
    const double g = safe_edge(u, SafeAxis::gamma, m, kappa, 0, dt);
    ASSERT_TRUE(std::isfinite(g));
    ASSERT_GT(g, 0);
    EXPECT_TRUE(safe_at_rest(u, m, kappa, g * 0.999, dt));
    EXPECT_FALSE(safe_at_rest(u, m, kappa, g * 1.001, dt));
    // Safe implies linearly stable: just inside the safe edge is inside the exact limit.
    EXPECT_FALSE(linearly_unstable(m, kappa, g * 0.999, dt, lambda));
    EXPECT_TRUE(safe_policy_guaranteed(u, m, kappa, dt));
    const double gamma = 0.5 * g;
    const double k = safe_edge(u, SafeAxis::kappa, m, kappa, gamma, dt);
    ASSERT_GT(k, kappa);
    EXPECT_TRUE(safe_at_rest(u, m, k * 0.999, gamma, dt));
    EXPECT_FALSE(safe_at_rest(u, m, k * 1.001, gamma, dt));
    const double lo_m = safe_edge(u, SafeAxis::m, m, kappa, gamma, dt);
    ASSERT_LT(lo_m, m);
    EXPECT_TRUE(safe_at_rest(u, lo_m * 1.001, kappa, gamma, dt));
    EXPECT_FALSE(safe_at_rest(u, lo_m * 0.999, kappa, gamma, dt));
    const double d = safe_edge(u, SafeAxis::dt, m, kappa, gamma, dt);
    ASSERT_GT(d, dt);
    EXPECT_TRUE(safe_at_rest(u, m, kappa, gamma, d * 0.999));
    EXPECT_FALSE(safe_at_rest(u, m, kappa, gamma, d * 1.001));
    EXPECT_FALSE(linearly_unstable(m, kappa, gamma, d * 0.999, lambda));
  }
}

TEST(SweepSafeEdge, ConfusionCountsEachPredictor) {
  const SceneSpec scene = test::shipped_scene("two-node");
  const SafeUnit u = unit_safe_bound(scene);
  const double lambda = unit_stiffness_eigenvalue(scene);
  const double m = 0.001, kappa = 0.001, dt = 0.05;
  const double edge = safe_edge(u, SafeAxis::gamma, m, kappa, 0, dt);
  SweepRow safe_ok, unsafe_div;
  safe_ok.m = unsafe_div.m = m;
  safe_ok.kappa = unsafe_div.kappa = kappa;
  safe_ok.dt = unsafe_div.dt = dt;
  safe_ok.gamma = 0.5 * edge;
  safe_ok.outcome = Outcome::restored;
  unsafe_div.gamma = 2 * m / dt * 1.5;  // gamma dt/m = 3 > 2: beyond every limit
  unsafe_div.outcome = Outcome::diverged;
  unsafe_div.unstabilisable = 4;
  const auto scores = divergence_confusion({safe_ok, unsafe_div}, u, lambda);
  ASSERT_EQ(scores.size(), 3u);
  for (const PredictorScore& s : scores) {
    SCOPED_TRACE(s.predictor);
    EXPECT_EQ(s.c.false_pos, 0u);
    EXPECT_EQ(s.c.false_neg, 0u);
    EXPECT_EQ(s.c.true_pos, 1u);
    EXPECT_EQ(s.c.true_neg, 1u);
  }
  const std::string md = confusion_markdown(scores);
  EXPECT_NE(md.find('|'), std::string::npos);
  EXPECT_FALSE(safe_summary_lines({safe_ok, unsafe_div}, DampingPolicy::fixed, u, lambda).empty());
  EXPECT_EQ(divergence_confusion({safe_ok}, u, std::nan("")).size(), 2u);
}

}  // namespace
}  // namespace dampbound
