// Tests of core/physics/detail/spring_batch_avx2.cpp: the AVX2 copy of the spring batch gives the
// portable copy's bits in every column that means something (spring_batch_test.cpp holds the
// portable copy to the scalar formulas), in every batch length. Skipped on a CPU without AVX2.
#include <gtest/gtest.h>

#include <cstring>

#include "core/physics/detail/spring_batch.hpp"
#include "tests/core/physics/detail/spring_batch_test_util.hpp"

namespace dampbound::detail {
namespace {

#if defined(__x86_64__)
bool same_double(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(SpringBatchAVX2, GivesThePortableCopysBits) {
  if (!step_isa_supported(StepIsa::avx2)) GTEST_SKIP() << "this CPU has no avx2";
  const test::BatchMesh m = test::batch_mesh();
  const SpringBatchInput in = spring_batch_input(m.model, m.x);
  const size_t ns = m.model.spec().springs.size();
  SpringBatch want, got;
  size_t checked = 0;
  for (bool forces : {true, false}) {
    for (bool blocks : {true, false}) {
      // Batches of every length from 1 to kSpringBatch, in turn, over the whole mesh.
      size_t count = 1;
      for (size_t first = 0; first < ns; first += count, count = count % kSpringBatch + 1) {
        const size_t n = std::min(count, ns - first);
        spring_batch_generic::compute(in, first, n, forces, blocks, want);
        spring_batch_avx2::compute(in, first, n, forces, blocks, got);
        for (size_t q = 0; q < n; ++q) {
          ASSERT_EQ(got.direction[q], want.direction[q]) << first + q;
          if (!want.direction[q]) continue;
          ++checked;
          if (forces) {
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(same_double(got.force[c][q], want.force[c][q]));
          }
          if (blocks) {
            ASSERT_EQ(got.compressed[q], want.compressed[q]);
            for (int c = 0; c < 6; ++c) ASSERT_TRUE(same_double(got.block[c][q], want.block[c][q]));
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(same_double(got.off[c][q], want.off[c][q]));
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 4 * (ns - 100));
}
#else
TEST(SpringBatchAVX2, GivesThePortableCopysBits) { GTEST_SKIP() << "not an x86-64 build"; }
#endif

}  // namespace
}  // namespace dampbound::detail
