#pragma once
// Shared helpers of the sweep tests: a small grid on a shipped scene.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/io/scene_file.hpp"
#include "core/sweep/grid.hpp"
#include "core/sweep/trials.hpp"

namespace dampbound::test {

inline SceneSpec shipped_scene(const std::string& name) {
  return load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/" + name + ".toml");
}

/// 2 m x 2 kappa x 2 zeta at one dt on `scene`'s stop rules, at most `max_iter` iterations.
inline SweepSpec small_sweep(const SceneSpec& scene, int max_iter = 200,
                             DampingPolicy policy = DampingPolicy::fixed) {
  SweepSpec s;
  s.m = parse_axis("--m", "0.001,0.002", AxisDomain::positive);
  s.kappa = parse_axis("--kappa", "0.001,0.004", AxisDomain::positive);
  s.gamma_mode = GammaMode::zeta;
  s.gamma = parse_axis("--zeta", "0.5,1", AxisDomain::non_negative);
  s.dt = parse_axis("--dt", "0.05", AxisDomain::positive);
  s.factor = parse_axis("--factor", "1", AxisDomain::non_negative);
  s.policy = policy;
  s.rules = scene.rules;
  s.rules.max_iterations = max_iter;
  return s;
}

/// Names the kernel copies a test runs, in its output and in its XML report (kernel_copies).
inline void say_kernel_copies(const std::string& copies) {
  ::testing::Test::RecordProperty("kernel_copies", copies);
  std::printf("[ copies   ] %s\n", copies.c_str());
}

/// The batched kernel built for `isa` gives run_reference's results (the one step() of core)
/// bit for bit on the two-node and paper-plane scenes, three policies, both stop rules.
inline void expect_kernel_matches_reference(KernelIsa isa) {
  say_kernel_copies(to_string(isa));
  for (const char* name : {"two-node", "paper-plane"}) {
    const SceneSpec scene = test::shipped_scene(name);
    for (DampingPolicy policy : {DampingPolicy::fixed, DampingPolicy::clamp, DampingPolicy::upper})
      for (StopRule rule : {StopRule::first_entry, StopRule::settled}) {
        SweepSpec s = test::small_sweep(scene, 120, policy);
        s.rules.rule = rule;
        const SweepGrid grid(s);
        std::vector<TrialParams> trials;
        for (std::uint64_t t = 0; t < grid.trials(); ++t) trials.push_back(grid.params(t));
        EXPECT_EQ(BatchKernel(scene, policy, s.rules, isa).isa(), isa);
        const auto got = run_batched(scene, policy, s.rules, trials, isa);
        ASSERT_EQ(got.size(), trials.size());
        for (size_t k = 0; k < trials.size(); ++k) {
          SCOPED_TRACE(std::string(name) + " " + to_string(policy) + " " + to_string(rule) +
                       " trial " + std::to_string(k));
          const TrialResult ref = run_reference(scene, policy, s.rules, trials[k]);
          EXPECT_EQ(got[k].outcome, ref.outcome);
          EXPECT_EQ(got[k].iterations, ref.iterations);
          EXPECT_EQ(std::memcmp(&got[k].max_displacement, &ref.max_displacement, sizeof(double)),
                    0);
          EXPECT_EQ(got[k].violations, ref.violations);
          EXPECT_EQ(got[k].unstabilisable, ref.unstabilisable);
          EXPECT_EQ(got[k].clamped, ref.clamped);
          EXPECT_EQ(got[k].first_entry, ref.first_entry);
          EXPECT_EQ(got[k].left_at, ref.left_at);
          EXPECT_EQ(got[k].settled_at, ref.settled_at);
        }
      }
  }
}

}  // namespace dampbound::test
