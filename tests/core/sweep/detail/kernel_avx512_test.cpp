// The batched kernel's avx512 copy: the same trials as run_reference (the one step() of core),
// bit for bit, under both stop rules and several policies. Skipped on a CPU without avx512.
#include "core/sweep/detail/kernel_avx512.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "core/sweep/trials.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

TEST(SweepKernelAVX512, MatchesRunReference) {
  if (!kernel_isa_supported(KernelIsa::avx512)) GTEST_SKIP() << "this CPU has no avx512";
  for (const char* name : {"two-node", "paper-plane"}) {
    const SceneSpec scene = test::shipped_scene(name);
    for (DampingPolicy policy : {DampingPolicy::fixed, DampingPolicy::clamp, DampingPolicy::upper})
      for (StopRule rule : {StopRule::first_entry, StopRule::settled}) {
        SweepSpec s = test::small_sweep(scene, 120, policy);
        s.rules.rule = rule;
        const SweepGrid grid(s);
        std::vector<TrialParams> trials;
        for (std::uint64_t t = 0; t < grid.trials(); ++t) trials.push_back(grid.params(t));
        EXPECT_EQ(BatchKernel(scene, policy, s.rules, KernelIsa::avx512).isa(), KernelIsa::avx512);
        const auto got = run_batched(scene, policy, s.rules, trials, KernelIsa::avx512);
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

TEST(SweepKernelAVX512, MakesAKernel) {
  if (!kernel_isa_supported(KernelIsa::avx512)) GTEST_SKIP() << "this CPU has no avx512";
  const SceneSpec scene = test::shipped_scene("two-node");
  EXPECT_NE(kernel_avx512::make(scene, DampingPolicy::fixed, scene.rules), nullptr);
}

}  // namespace
}  // namespace dampbound
