// Tests of core/physics/step_isa.cpp: the names of step()'s compiled copies, what this CPU runs, and
// that step() gives the same bits with every copy it can run (positions, velocities, bounds,
// effective damping and counts), under every integrator, with and without SPEC 9's row sums,
// on one thread and on two.
#include "dampbound/physics/step_isa.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "dampbound/physics/step.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

TEST(StepIsa, NamesRoundTrip) {
  for (StepIsa isa : {StepIsa::best, StepIsa::generic, StepIsa::avx2}) {
    const auto parsed = parse_step_isa(to_string(isa));
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(*parsed, isa);
  }
  EXPECT_FALSE(parse_step_isa("avx512").has_value());
  EXPECT_FALSE(parse_step_isa("AVX2").has_value());
  EXPECT_FALSE(parse_step_isa("").has_value());
}

TEST(StepIsa, BestIsACopyThisCpuRuns) {
  EXPECT_TRUE(step_isa_supported(StepIsa::generic));
  EXPECT_TRUE(step_isa_supported(StepIsa::best));
  const StepIsa best = best_step_isa();
  EXPECT_NE(best, StepIsa::best);
  EXPECT_TRUE(step_isa_supported(best));
  EXPECT_EQ(best_step_isa(), best);  // decided once
  std::printf("this CPU runs step()'s %s copy\n", to_string(best));
}

template <class T>
bool same_vector_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(StepIsa, EveryCopyGivesStepsSameBits) {
  if (!step_isa_supported(StepIsa::avx2)) GTEST_SKIP() << "this CPU runs the generic copy only";
  const ModelSpec spec = test::cube_lattice(14, 0.5, [](ModelSpec& m, int i, int a, int b, int) {
    m.mass_scale.back() = 1 + (i % 7) * 0.25;
    m.anchor_scale.back() = i % 3 == 0 ? 2.0 : 0.0;
    m.fixed.back() = b == 0 && a % 4 == 0;
  });
  for (Integrator in : {Integrator::semi_implicit_euler, Integrator::forward_euler,
                        Integrator::verlet, Integrator::rk4}) {
    for (DampingPolicy policy : {DampingPolicy::clamp, DampingPolicy::safe}) {
      for (int threads : {1, 2}) {
        SCOPED_TRACE(std::string(to_string(in)) + " " + to_string(policy) + " " +
                     std::to_string(threads) + " threads");
        Params p;
        p.integrator = in;
        p.policy = policy;
        p.dt = 0.02;
        const Model m = compile_model(spec, p);
        State a = rest_state(m);
        test::shake(a.x, 0.2, 5);
        State b = a;
        StepWorkspace wa, wb;
        wa.pass.isa = StepIsa::generic;
        wb.pass.isa = StepIsa::avx2;
        wa.pass.threads.set_threads(threads);
        wb.pass.threads.set_threads(threads);
        wa.pass.threads.set_grain(1000);
        wb.pass.threads.set_grain(1000);
        int compressed = 0;
        for (int k = 0; k < 12; ++k) {
          const StepStats sa = step(m, p, a, wa), sb = step(m, p, b, wb);
          ASSERT_EQ(std::memcmp(&sa.max_displacement, &sb.max_displacement, sizeof(double)), 0);
          ASSERT_EQ(sa.violating, sb.violating);
          ASSERT_EQ(sa.clamped, sb.clamped);
          ASSERT_EQ(sa.unguaranteed, sb.unguaranteed);
          ASSERT_EQ(sa.compressed_springs, sb.compressed_springs);
          ASSERT_EQ(sa.zero_length_springs, sb.zero_length_springs);
          compressed += sa.compressed_springs;
          ASSERT_TRUE(same_vector_bits(a.x, b.x)) << "step " << k;
          ASSERT_TRUE(same_vector_bits(a.v, b.v)) << "step " << k;
          ASSERT_TRUE(same_vector_bits(wa.force, wb.force));
          ASSERT_TRUE(same_vector_bits(wa.safe_row_sum, wb.safe_row_sum));
          ASSERT_TRUE(same_vector_bits(wa.upper_bound, wb.upper_bound));
          ASSERT_TRUE(same_vector_bits(wa.safe_bound, wb.safe_bound));
          ASSERT_TRUE(same_vector_bits(wa.gamma_eff, wb.gamma_eff));
        }
        EXPECT_GT(compressed, 0);
      }
    }
  }
}

}  // namespace
}  // namespace dampbound
