// Session: the trace it keeps, and a trial that stops when asked (the plain sweep's Ctrl-C).
#include "core/session.hpp"

#include <gtest/gtest.h>

#include <atomic>

#include "core/sweep/kernel.hpp"
#include "core/io/scene_file.hpp"
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

}  // namespace
}  // namespace dampbound
