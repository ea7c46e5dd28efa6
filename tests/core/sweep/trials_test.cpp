// Trials outside a sweep: conversions, trial params, the spring schedule, run_batched against
// run_reference.
#include "core/sweep/trials.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <map>

#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

TEST(SweepTrials, TrialParamsFillTheTrialsValues) {
  Params base;
  TrialParams t;
  t.m = 0.003;
  t.kappa = 0.007;
  t.gamma = 0.0005;
  t.dt = 0.02;
  t.factor = 1.25;
  const Params p = trial_params(base, DampingPolicy::upper, t);
  EXPECT_EQ(p.m, t.m);
  EXPECT_EQ(p.kappa, t.kappa);
  EXPECT_EQ(p.gamma, t.gamma);
  EXPECT_EQ(p.dt, t.dt);
  EXPECT_EQ(p.factor, t.factor);
  EXPECT_EQ(p.policy, DampingPolicy::upper);
}

TEST(SweepTrials, ScheduleKeepsEachNodesSpringOrder) {
  const SceneSpec scene = test::shipped_scene("paper-plane");
  const ModelSpec& model = scene.model;
  const std::vector<int> order = spring_schedule(model);
  ASSERT_EQ(order.size(), model.springs.size());
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (size_t k = 0; k < sorted.size(); ++k) EXPECT_EQ(sorted[k], static_cast<int>(k));
  std::map<int, int> last;  // node -> last spring index applied to it
  for (int s : order)
    for (int node : {model.springs[static_cast<size_t>(s)].i, model.springs[static_cast<size_t>(s)].j}) {
      auto it = last.find(node);
      if (it != last.end()) {
        EXPECT_LT(it->second, s) << "node " << node;
      }
      last[node] = s;
    }
}

TEST(SweepTrials, BatchedEqualsReferenceAndCancelStops) {
  const SceneSpec scene = test::shipped_scene("two-node");
  const SweepSpec s = test::small_sweep(scene, 150);
  const SweepGrid grid(s);
  std::vector<TrialParams> trials;
  for (std::uint64_t t = 0; t < grid.trials(); ++t) trials.push_back(grid.params(t));
  const auto batched = run_batched(scene, s.policy, s.rules, trials, KernelIsa::generic);
  ASSERT_EQ(batched.size(), trials.size());
  for (size_t k = 0; k < trials.size(); ++k) {
    const TrialResult ref = run_reference(scene, s.policy, s.rules, trials[k]);
    EXPECT_EQ(batched[k].outcome, ref.outcome);
    EXPECT_EQ(batched[k].iterations, ref.iterations);
    EXPECT_EQ(std::memcmp(&batched[k].max_displacement, &ref.max_displacement, sizeof(double)), 0);
    EXPECT_EQ(batched[k].violations, ref.violations);
  }
  const std::atomic<bool> cancel{true};
  EXPECT_TRUE(run_batched(scene, s.policy, s.rules, trials, KernelIsa::generic, &cancel).empty());
  EXPECT_EQ(run_reference(scene, s.policy, s.rules, trials[0], &cancel).outcome, Outcome::running);
}

}  // namespace
}  // namespace dampbound
