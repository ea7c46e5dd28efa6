#include "core/analysis/substeps.hpp"

#include <gtest/gtest.h>

#include "core/scene.hpp"

namespace dampbound {
namespace {

TEST(Substeps, FewestCountBelowAnExclusiveLimit) {
  EXPECT_EQ(substeps_below(0.05, 0.5), 1);     // already stable at n = 1
  EXPECT_EQ(substeps_below(1.0, 0.5), 3);      // 1/2 = 0.5 is not below 0.5
  EXPECT_EQ(substeps_below(1.0, 0.3), 4);
  EXPECT_EQ(substeps_below(1.0, 0.0), 0);      // no limit known
  EXPECT_EQ(substeps_below(1.0, 1e-300), 0);   // beyond kMaxSubsteps
  EXPECT_EQ(substeps_below(1.0, std::numeric_limits<double>::infinity()), 1);
}

TEST(Substeps, PaperPlaneAtOneFrameIsOneSubstepAndVerified) {
  SceneSpec s = paper_plane_scene(8);
  StopRules r = s.rules;
  r.max_iterations = 400;
  const SubstepSuggestion g = suggest_substeps(s, s.params, r, 0.05);
  EXPECT_EQ(g.exact.n, 1);
  EXPECT_EQ(g.safe.n, 1);
  EXPECT_TRUE(g.exact.ran && g.exact.run.verified());
}

TEST(Substeps, AFrameLongerThanTheLimitNeedsMoreAndAFailedRunIsReported) {
  SceneSpec s = paper_plane_scene(8);
  StopRules r = s.rules;
  r.max_iterations = 2;  // too short to settle: the verification must say so, not hide it
  const SubstepSuggestion g = suggest_substeps(s, s.params, r, 2.0);
  EXPECT_GT(g.exact.n, 1);
  EXPECT_GE(g.safe.n, g.exact.n);  // the safe bound is sufficient, never looser than exact
  EXPECT_LT(g.exact.dt, g.exact.limit);
  EXPECT_GE(2.0 / (g.exact.n - 1), g.exact.limit);  // one fewer would not be below it
  EXPECT_TRUE(g.exact.ran);
  EXPECT_FALSE(g.exact.run.verified());
}

}  // namespace
}  // namespace dampbound
