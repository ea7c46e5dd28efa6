// The protocol's outcomes (SPEC 5) and the session's mid-run changes.
#include "dampbound/run/protocol.hpp"

#include <gtest/gtest.h>

#include "core/io/report.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/run/session.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

SceneSpec paper_plane() { return load_scene(test::source_path("scenes/paper-plane.toml")); }
SceneSpec two_node() { return load_scene(test::source_path("scenes/two-node.toml")); }

TEST(Judge, Thresholds) {
  StopRules r;  // reference 5: restore below 0.05, diverge above 500
  StepStats s;
  s.iteration = 3;
  s.max_displacement = 0.049;
  EXPECT_EQ(judge(r, s), Outcome::restored);
  s.max_displacement = 0.05;
  EXPECT_EQ(judge(r, s), Outcome::running);
  s.max_displacement = 500.1;
  EXPECT_EQ(judge(r, s), Outcome::diverged);
  s.max_displacement = 1;
  s.finite = false;
  EXPECT_EQ(judge(r, s), Outcome::diverged);
  s.finite = true;
  s.iteration = 1000;
  EXPECT_EQ(judge(r, s), Outcome::not_restored);
}

TEST(Protocol, HeavilyDampedTwoNodeRestores) {
  SceneSpec s = two_node();
  Params p = s.params;
  p.gamma = 4 * lower_bound(p.m, p.kappa);
  s.rules.rule = StopRule::first_entry;  // the paper's protocol, named
  Session session(s, p, s.rules);
  const RunResult& r = session.run_to_end();
  EXPECT_EQ(r.outcome, Outcome::restored);
  EXPECT_GT(r.iterations, 1);
  EXPECT_LT(r.max_displacement, 0.01 * 0.5);
  EXPECT_EQ(r.violations, 0);  // gamma is above the lower bound and under the upper one
}

TEST(Protocol, UndampedPaperPlaneNeverRestores) {
  SceneSpec s = paper_plane();
  Params p = s.params;
  p.gamma = 0;  // the step conserves a modified energy: the wave never dies out
  s.rules.rule = StopRule::first_entry;  // the paper's protocol, named
  Session session(s, p, s.rules);
  const RunResult& r = session.run_to_end();
  EXPECT_EQ(r.outcome, Outcome::not_restored);
  EXPECT_EQ(r.iterations, 1000);
  EXPECT_EQ(r.violations, 1296 * 1000);  // gamma = 0 is below the lower bound everywhere
}

TEST(Protocol, UndampedTwoNodePassesThroughRestAndCounts) {
  // SPEC 5's restore test is instantaneous: a lone undamped oscillator that passes within
  // 1% of rest counts as restored at that iteration (here the first zero crossing, near
  // t = (pi/2) sqrt(m/kappa) = 1.57 s, iteration ~31).
  SceneSpec s = two_node();
  Params p = s.params;
  p.gamma = 0;
  s.rules.rule = StopRule::first_entry;  // the paper's protocol, named
  Session session(s, p, s.rules);
  const RunResult& r = session.run_to_end();
  EXPECT_EQ(r.outcome, Outcome::restored);
  EXPECT_NEAR(r.iterations, 31, 2);
}

TEST(Protocol, UndampedStiffPaperPlaneDiverges) {
  SceneSpec s = paper_plane();
  Params p = s.params;
  p.kappa = 1, p.m = 0.001, p.gamma = 0;  // lambda dt^2 far above 4
  s.rules.rule = StopRule::first_entry;  // the paper's protocol, named
  Session session(s, p, s.rules);
  const RunResult& r = session.run_to_end();
  EXPECT_EQ(r.outcome, Outcome::diverged);
  EXPECT_LT(r.iterations, 100);
  const std::string json = result_json("x", p, s.rules, 666, r);
  EXPECT_EQ(json.find("nan"), std::string::npos);
  EXPECT_NE(json.find("\"outcome\":\"diverged\""), std::string::npos);
}

TEST(Protocol, SessionIsThePureStepPlusAccumulate) {
  // A bare loop over step() and accumulate() gives the Session's verdict and counts: the
  // Session adds nothing to the physics, only the watched node's samples.
  SceneSpec s = paper_plane();
  Params p = s.params;
  p.gamma = 0.001;
  s.rules.rule = StopRule::first_entry;  // the paper's protocol, named
  Session session(s, p, s.rules);
  const RunResult a = session.run_to_end();
  const Model model = compile_model(s.model, p);
  State st = initial_state(s);
  StepWorkspace ws;
  RunResult b;
  while (b.outcome == Outcome::running) accumulate(b, step(model, p, st, ws), s.rules);
  EXPECT_EQ(a.outcome, b.outcome);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.max_displacement, b.max_displacement);
  EXPECT_EQ(a.violations, b.violations);
  EXPECT_EQ(session.trace().back().watched.displacement, displacement(model, st, s.watched));
}

TEST(Protocol, UpperPolicyAtRestAndAboveTheBound) {
  // Upper policy at a factor above 1 sets gamma above the bound: every moving node violates.
  SceneSpec s = paper_plane();
  Params p = s.params;
  p.policy = DampingPolicy::upper;
  p.factor = 1.05;
  p.kappa = 0.1, p.m = 0.005;
  s.rules.rule = StopRule::first_entry;  // the paper's protocol, named
  Session session(s, p, s.rules);
  const StepSample& first = session.step_once();
  // At t = 0 every v is 0: gamma_hi = inf, the policy gives 0, below the lower bound.
  EXPECT_EQ(first.violating, 1296);
  EXPECT_EQ(first.unstabilisable, 0);
  EXPECT_EQ(first.watched.gamma_eff, 0.0);
  const StepSample second = session.step_once();
  EXPECT_GT(second.violating, 0);
  EXPECT_NEAR(second.watched.gamma_eff, 1.05 * second.watched.upper, 1e-15);
}

TEST(Session, ParameterChangeTakesEffectNextStep) {
  Session session(paper_plane());
  session.step_once();
  EXPECT_DOUBLE_EQ(session.trace().back().watched.lower, 0.002);
  Params p = session.params();
  p.kappa = 0.004;  // lower bound 2 sqrt(0.001 * 0.004) = 0.004
  session.set_params(p);
  session.step_once();
  EXPECT_DOUBLE_EQ(session.trace().back().watched.lower, 0.004);
  EXPECT_EQ(session.trace().back().iteration, 2);
}

TEST(Session, CutRemovesCrossingSpringsAndBoundsReact) {
  SceneSpec s = paper_plane();
  Session cut(s), whole(s);
  for (int k = 0; k < 5; ++k) cut.step_once(), whole.step_once();
  // A cut along x = 10.0 cm between columns a = 17 and 18, through the whole mesh: every
  // edge (a=17)-(a=18) and every diagonal crossing it, 36 + 35 springs.
  const double from[2] = {10.0, -1.0}, to[2] = {10.0, 25.0};
  const auto crossing = springs_crossing(cut.model(), cut.state().x, from, to);
  EXPECT_EQ(crossing.size(), 71u);
  EXPECT_EQ(cut.cut(crossing), 71);
  EXPECT_EQ(cut.model().spec().spring_count(), 3745 - 71);
  const StepSample a = cut.step_once(), b = whole.step_once();
  EXPECT_NE(a.watched.upper, b.watched.upper);  // the node next to the cut lost springs
  cut.reset();
  EXPECT_EQ(cut.model().spec().spring_count(), 3745);
  EXPECT_TRUE(cut.trace().empty());
}

TEST(Session, ScheduledCutFromScene) {
  SceneSpec s = paper_plane();
  s.cuts.push_back({3, {10.0, -1}, {10.0, 25}});  // along x = 10.0 cm after 3 steps
  Session session(s);
  for (int k = 0; k < 3; ++k) session.step_once();
  EXPECT_EQ(session.model().spec().spring_count(), 3745);
  session.step_once();
  EXPECT_EQ(session.springs_cut(), 71);
}

TEST(Session, CurrentSceneHasTheCutsMadeSoFar) {
  SceneSpec s = paper_plane();
  s.cuts.push_back({3, {-1, 10.0}, {25, 10.0}});  // scripted: along z = 10.0 cm after 3 steps
  Session session(s);
  EXPECT_EQ(session.current_scene().model.spring_count(), 3745);
  ASSERT_EQ(session.current_scene().cuts.size(), 1u);  // not reached yet
  // By hand, before the scripted cut: along x = 10.0 cm.
  const double from[2] = {10.0, -1.0}, to[2] = {10.0, 25.0};
  EXPECT_EQ(session.cut(springs_crossing(session.model(), session.state().x, from, to)), 71);
  for (int k = 0; k < 3; ++k) session.step_once();
  SceneSpec now = session.current_scene();
  EXPECT_EQ(now.model.spring_count(), 3745 - 71);
  ASSERT_EQ(now.cuts.size(), 1u);  // due before the next step: still to come
  session.step_once();
  now = session.current_scene();
  EXPECT_EQ(now.model.spring_count(), session.model().spec().spring_count());
  EXPECT_LT(now.model.spring_count(), 3745 - 71);
  EXPECT_TRUE(now.cuts.empty());
  // A fresh run of the current scene starts from the perturbed state on the cut mesh, with
  // the session's parameters applied to it.
  Params p = session.params();
  p.kappa *= 2;
  Session fresh(now, p, session.rules());
  EXPECT_EQ(fresh.model().spec().spring_count(), now.model.spring_count());
  EXPECT_DOUBLE_EQ(fresh.model().spring_kappa.front(), 2 * session.model().spring_kappa.front());
  EXPECT_DOUBLE_EQ(fresh.state().x[666].y(), 5.0);
  EXPECT_EQ(fresh.state().iteration, 0);
}

TEST(Session, PerturbAddsDisplacementAgain) {
  Session session(paper_plane());
  session.perturb();
  EXPECT_DOUBLE_EQ(session.state().x[666].y(), 10.0);
  session.displace(0, Vec3(0, 1, 0));
  EXPECT_DOUBLE_EQ(session.state().x[0].y(), 1.0);
}

}  // namespace
}  // namespace dampbound
