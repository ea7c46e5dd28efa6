// Session: the trace it keeps, a trial that stops when asked (the plain sweep's Ctrl-C), and
// the model it shares with a worker thread.
#include "dampbound/run/session.hpp"

#include <gtest/gtest.h>

#include <atomic>

#include "core/io/scene_file.hpp"
#include "core/io/scene_write.hpp"
#include "core/sweep/kernel.hpp"
#include "core/sweep/trials.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

TEST(Session, WithoutATraceMemoryStaysFlat) {
  // A run that writes no trace kept about 100 bytes per iteration (10 GB at 1e8).
  const SceneSpec scene = load_scene(test::source_path("scenes/two-node.toml"));
  Session all(scene), last(scene);
  last.set_keep_trace(false);
  const RunResult& a = all.run_to_end();
  const RunResult& b = last.run_to_end();
  ASSERT_GT(a.iterations, 10);
  EXPECT_EQ(all.trace().size(), static_cast<size_t>(a.iterations));
  ASSERT_EQ(last.trace().size(), 1u);
  // The same run: the verdict and the last step agree.
  EXPECT_EQ(b.outcome, a.outcome);
  EXPECT_EQ(b.iterations, a.iterations);
  EXPECT_EQ(b.max_displacement, a.max_displacement);
  EXPECT_EQ(last.trace().back().max_displacement, all.trace().back().max_displacement);
  EXPECT_EQ(last.trace().back().iteration, all.trace().back().iteration);
}

TEST(Session, APlainTrialStopsWhenCancelled) {
  const SceneSpec scene = load_scene(test::source_path("scenes/paper-plane.toml"));
  StopRules rules = scene.rules;
  rules.max_iterations = 100000000;  // would run for hours
  TrialParams p;
  p.gamma = 0;
  std::atomic<bool> cancel{true};
  const TrialResult r = run_reference(scene, scene.params.policy, rules, p, &cancel);
  EXPECT_EQ(r.outcome, Outcome::running);
  EXPECT_EQ(r.iterations, 0);
}

TEST(Session, ASharedModelKeepsItsValuesWhileTheSessionGoesOn) {
  // The tuner's analysis worker reads shared_model() while the frames change the parameters
  // and cut springs: the snapshot must keep what it was taken with, and the run must step
  // exactly as a session that was never shared.
  const SceneSpec scene = load_scene(test::source_path("scenes/paper-plane.toml"));
  Session shared(scene), alone(scene);
  for (int k = 0; k < 5; ++k) {
    shared.step_once();
    alone.step_once();
  }
  Params p = scene.params;
  p.kappa *= 3;
  p.m *= 0.5;

  // Nobody holds the model: a parameter change refills it in place.
  const Model* before = &alone.model();
  alone.set_params(p);
  EXPECT_EQ(&alone.model(), before);

  const std::shared_ptr<const Model> snapshot = shared.shared_model();
  EXPECT_EQ(snapshot.get(), &shared.model());  // shared, not copied
  const std::vector<double> kappa_then = snapshot->spring_kappa, mass_then = snapshot->mass;
  shared.set_params(p);
  EXPECT_NE(&shared.model(), snapshot.get());  // held by the worker: the session copied it
  EXPECT_EQ(snapshot->spring_kappa, kappa_then);
  EXPECT_EQ(snapshot->mass, mass_then);
  EXPECT_EQ(shared.model().spring_kappa, alone.model().spring_kappa);
  EXPECT_EQ(shared.model().mass, alone.model().mass);
  EXPECT_EQ(shared.model().lower_bound, alone.model().lower_bound);

  const int springs_then = snapshot->spec().spring_count();
  ASSERT_EQ(shared.cut({0, 1, 2}), 3);
  ASSERT_EQ(alone.cut({0, 1, 2}), 3);
  EXPECT_EQ(snapshot->spec().spring_count(), springs_then);
  for (int k = 0; k < 20; ++k) {
    shared.step_once();
    alone.step_once();
  }
  EXPECT_EQ(shared.state().x, alone.state().x);
  EXPECT_EQ(shared.state().v, alone.state().v);
}

TEST(Session, TheSceneAsRunKeepsEveryFieldButTheCutsPassed) {
  // scene_as_run copies the scene field by field (to leave the loaded mesh alone): written
  // back as TOML, the scene at iteration 0 with its own mesh is the scene, for every shipped
  // scene; past a cut's iteration the cut is gone and the mesh is the one given.
  for (const char* name : {"paper-plane", "paper-plane-cut", "paper-plane-policies",
                           "paper-plane-safe", "paper-plane-stiff", "paper-plane-tuned",
                           "quad-cloth", "stiff-region", "tissue-block", "tissue-cap",
                           "two-node-damping", "two-node"}) {
    SCOPED_TRACE(name);
    const std::string path = test::source_path(std::string("scenes/") + name + ".toml");
    const SceneSpec scene = load_scene(path);
    EXPECT_EQ(scene_toml(scene_as_run(scene, scene.model, 0), path), scene_toml(scene, path));
  }
  const SceneSpec scene = load_scene(test::source_path("scenes/paper-plane-cut.toml"));
  ASSERT_FALSE(scene.cuts.empty());
  Session s(scene);
  while (s.state().iteration <= scene.cuts.front().iteration) s.step_once();
  const SceneSpec now = s.current_scene();
  EXPECT_EQ(now.cuts.size(), scene.cuts.size() - 1);
  EXPECT_LT(now.model.springs.size(), scene.model.springs.size());
  EXPECT_TRUE(same_topology(now.model, s.model()));
  EXPECT_EQ(now.name, scene.name);
}

TEST(Session, AResetLeavesNoStepResultsBehind) {
  // A run that diverges, then Reset: the workspace holds no step's status, bounds or damping,
  // exactly as a new session's (the tuner colours every node "within" again).
  const SceneSpec scene = load_scene(test::source_path("scenes/two-node.toml"));
  Params p = scene.params;
  p.dt = 5;
  Session s(scene, p, scene.rules);
  const Session fresh(scene, p, scene.rules);
  for (int k = 0; k < 20 && s.running(); ++k) s.step_once();
  ASSERT_FALSE(s.workspace().status.empty());
  s.reset();
  EXPECT_EQ(s.state().iteration, 0);
  EXPECT_EQ(s.workspace().status.size(), fresh.workspace().status.size());
  EXPECT_EQ(s.workspace().upper_bound.size(), fresh.workspace().upper_bound.size());
  EXPECT_EQ(s.workspace().gamma_eff.size(), fresh.workspace().gamma_eff.size());
  EXPECT_EQ(s.workspace().safe_bound.size(), fresh.workspace().safe_bound.size());
  s.step_once();  // and it steps again as a new one does
  EXPECT_EQ(s.workspace().status.size(), static_cast<size_t>(s.model().spec().node_count()));
}

}  // namespace
}  // namespace dampbound
