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
  test::expect_kernel_matches_reference(KernelIsa::avx512);
}

TEST(SweepKernelAVX512, MakesAKernel) {
  if (!kernel_isa_supported(KernelIsa::avx512)) GTEST_SKIP() << "this CPU has no avx512";
  const SceneSpec scene = test::shipped_scene("two-node");
  EXPECT_NE(kernel_avx512::make(scene, DampingPolicy::fixed, scene.rules), nullptr);
}

}  // namespace
}  // namespace dampbound
