// The run-time choice of the batched kernel's instruction set: every variant this CPU runs
// (generic, AVX2, AVX-512; core/sweep_kernel_avx*.cpp) gives step()'s trajectory bit for bit
// on trials that restore, diverge and run to the limit, under every policy and both
// integrators the kernel supports.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

#include "core/sweep/kernel.hpp"
#include "core/sweep/trials.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

std::vector<TrialParams> mixed_trials() {
  std::vector<TrialParams> trials;
  for (double zeta : {0.2, 1.0})
    for (double r : {1.0, 60.0, 400.0})
      for (double factor : {1.0, 1.05}) {
        TrialParams t;
        t.m = 0.002;
        t.kappa = r * t.m;
        t.gamma = zeta * lower_bound(t.m, t.kappa);
        t.factor = factor;
        trials.push_back(t);
      }
  return trials;
}

TEST(SweepKernelDispatch, NamesRoundTrip) {
  for (KernelIsa isa : {KernelIsa::best, KernelIsa::generic, KernelIsa::avx2, KernelIsa::avx512})
    EXPECT_EQ(parse_kernel_isa(to_string(isa)), isa);
  EXPECT_FALSE(parse_kernel_isa("sse9"));
  EXPECT_TRUE(kernel_isa_supported(KernelIsa::generic));
}

TEST(SweepKernelDispatch, BestIsTheWidestSupportedAndNeverBest) {
  const KernelIsa best = best_kernel_isa();
  EXPECT_NE(best, KernelIsa::best);
  EXPECT_TRUE(kernel_isa_supported(best));
  if (!std::getenv("DAMPBOUND_KERNEL_ISA")) {
#if defined(__AVX512F__)
    const KernelIsa widest = KernelIsa::generic;  // a DAMPBOUND_NATIVE build's own copy
#else
    const KernelIsa widest = kernel_isa_supported(KernelIsa::avx512) ? KernelIsa::avx512
                             : kernel_isa_supported(KernelIsa::avx2) ? KernelIsa::avx2
                                                                     : KernelIsa::generic;
#endif
    EXPECT_EQ(best, widest);
  }
  SceneSpec scene = paper_plane_scene(4);
  EXPECT_EQ(BatchKernel(scene, DampingPolicy::fixed, scene.rules).isa(), best);
}

TEST(SweepKernelDispatch, EveryVariantMatchesStepBitForBit) {
  SceneSpec scene = paper_plane_scene(8);
  StopRules rules = scene.rules;
  rules.rule = StopRule::first_entry;  // the outcomes counted below are the paper's
  rules.max_iterations = 150;
  const auto trials = mixed_trials();
  int variants = 0;
  std::string ran, skipped;
  for (KernelIsa isa : {KernelIsa::generic, KernelIsa::avx2, KernelIsa::avx512})
    (kernel_isa_supported(isa) ? ran : skipped) += std::string(" ") + to_string(isa);
  test::say_kernel_copies("ran:" + ran +
                          (skipped.empty() ? "" : "; skipped, not on this CPU:" + skipped));
  for (Integrator integ : {Integrator::semi_implicit_euler, Integrator::forward_euler}) {
    scene.params.integrator = integ;
    for (DampingPolicy p :
         {DampingPolicy::fixed, DampingPolicy::clamp, DampingPolicy::upper, DampingPolicy::lower}) {
      std::vector<TrialResult> ref;
      std::map<Outcome, int> seen;
      for (const TrialParams& t : trials) {
        ref.push_back(run_reference(scene, p, rules, t));
        ++seen[ref.back().outcome];
      }
      if (integ == Integrator::semi_implicit_euler && p == DampingPolicy::fixed) {
        // The sample covers every outcome, so a variant cannot match by luck.
        EXPECT_GT(seen[Outcome::restored], 0);
        EXPECT_GT(seen[Outcome::diverged], 0);
        EXPECT_GT(seen[Outcome::not_restored], 0);
      }
      for (KernelIsa isa : {KernelIsa::generic, KernelIsa::avx2, KernelIsa::avx512}) {
        if (!kernel_isa_supported(isa)) continue;
        ++variants;
        const auto got = run_batched(scene, p, rules, trials, isa);
        for (size_t k = 0; k < trials.size(); ++k) {
          SCOPED_TRACE(std::string(to_string(isa)) + " " + to_string(p) + " " + to_string(integ) +
                       " trial " + std::to_string(k));
          EXPECT_EQ(got[k].outcome, ref[k].outcome);
          EXPECT_EQ(got[k].iterations, ref[k].iterations);
          EXPECT_TRUE(same_bits(got[k].max_displacement, ref[k].max_displacement))
              << got[k].max_displacement << " vs " << ref[k].max_displacement;
          EXPECT_EQ(got[k].violations, ref[k].violations);
          EXPECT_EQ(got[k].unstabilisable, ref[k].unstabilisable);
          EXPECT_EQ(got[k].clamped, ref[k].clamped);
        }
      }
    }
  }
  EXPECT_GE(variants, 8);  // at least the generic variant, for 2 integrators x 4 policies
}

}  // namespace
}  // namespace dampbound
