// The batched kernel's avx2 copy: the same trials as run_reference (the one step() of core),
// bit for bit, under both stop rules and several policies. Skipped on a CPU without avx2.
#include "core/sweep/detail/kernel_avx2.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "core/sweep/trials.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

TEST(SweepKernelAVX2, MatchesRunReference) {
  if (!kernel_isa_supported(KernelIsa::avx2)) GTEST_SKIP() << "this CPU has no avx2";
  test::expect_kernel_matches_reference(KernelIsa::avx2);
}

TEST(SweepKernelAVX2, MakesAKernel) {
  if (!kernel_isa_supported(KernelIsa::avx2)) GTEST_SKIP() << "this CPU has no avx2";
  const SceneSpec scene = test::shipped_scene("two-node");
  EXPECT_NE(kernel_avx2::make(scene, DampingPolicy::fixed, scene.rules), nullptr);
}

}  // namespace
}  // namespace dampbound
