#include "core/analysis/substeps.hpp"

#include <gtest/gtest.h>

#include "dampbound/run/scene.hpp"

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
  EXPECT_FALSE(g.exact.verified());
  // No count settles in 2 iterations: the search by running finds none, and there is no
  // answer (the CLI exits 1).
  EXPECT_GT(g.search_runs, 0);
  EXPECT_LE(g.search_runs, kMaxSearchRuns);
  EXPECT_EQ(g.by_running.n, 0);
  EXPECT_EQ(g.answer(), nullptr);
}

// A count's run covers the scene's simulated time: a finer dt runs more iterations.
TEST(Substeps, AFinerStepRunsOverTheScenesTime) {
  EXPECT_EQ(verify_iterations(1000, 50.0, 0.05), 1000);
  EXPECT_EQ(verify_iterations(1000, 50.0, 1.0 / 60), 3000);
  EXPECT_EQ(verify_iterations(1000, 50.0, 0.001), 4000);  // kVerifySpan caps it
  EXPECT_EQ(verify_iterations(1000, 0.2, 0.0005), 1000);  // never fewer than the scene's
}

// The paper plane at kappa/m = 1000 and gamma = 0.02 with a frame of 0.1 s: the exact limit
// at rest gives 5 substeps (dt = 0.02 s < 0.0202 s), but the 5 cm pull (9 spacings) stretches
// the mesh beyond its rest stiffness and the run diverges; the search runs finer counts and
// finds the fewest that settles.
TEST(Substeps, WhereTheExactCountFailsTheFewestCountThatSettlesIsFoundByRunning) {
  SceneSpec s = paper_plane_scene();
  Params p = s.params;
  p.m = 0.001;
  p.kappa = 1;
  p.gamma = 0.02;
  const SubstepSuggestion g = suggest_substeps(s, p, s.rules, 0.1);
  ASSERT_EQ(g.exact.n, 5);
  EXPECT_EQ(g.exact.run.result.outcome, Outcome::diverged);
  ASSERT_GT(g.by_running.n, g.exact.n);
  EXPECT_TRUE(g.by_running.verified());
  EXPECT_EQ(g.by_running.dt, 0.1 / g.by_running.n);
  EXPECT_EQ(g.answer(), &g.by_running);
  // The bracket is closed and real: one count fewer, run by hand, does not settle.
  EXPECT_EQ(g.failed_at_most, g.by_running.n - 1);
  Params fewer = p;
  fewer.dt = 0.1 / g.failed_at_most;
  StopRules r = s.rules;
  r.max_iterations = verify_iterations(s.rules.max_iterations, s.rules.max_iterations * s.params.dt,
                                       fewer.dt);
  EXPECT_FALSE(verify_run(s, fewer, r, "one fewer").verified());
  // At gamma 0.005 neither the exact nor the safe count settles: the search itself runs
  // (a count a quarter up, then the bisection) and closes the bracket.
  p.gamma = 0.005;
  const SubstepSuggestion h = suggest_substeps(s, p, s.rules, 0.1);
  EXPECT_FALSE(h.exact.verified());
  EXPECT_FALSE(h.safe.verified());
  EXPECT_GE(h.search_runs, 2);
  ASSERT_GT(h.by_running.n, 0);
  EXPECT_TRUE(h.by_running.verified());
  EXPECT_EQ(h.failed_at_most, h.by_running.n - 1);
  EXPECT_EQ(h.answer(), &h.by_running);
}

}  // namespace
}  // namespace dampbound
