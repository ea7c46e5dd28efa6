// Tests of core/physics/detail/spring_batch.cpp, the portable copy: every column of a batch has the
// bits of the scalar formulas it replaces (SPEC 1's force with Vec3 and norm(), SPEC 7's
// block, SPEC 9's row sums of |B| times w), for every batch length and offset, on a shaken
// lattice with compressed springs, a spring of zero length and one with a NaN end. The
// copies for other instruction sets are held to this one (spring_batch_avx2_test.cpp).
#include "core/physics/detail/spring_batch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "core/physics/detail/spring_block.hpp"
#include "tests/core/physics/detail/spring_batch_test_util.hpp"

namespace dampbound::detail {
namespace {

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// The scalar formulas, spring k at positions x.
struct Scalar {
  bool direction = false, compressed = false;
  double force[3] = {}, block[6] = {}, off[3] = {};
};

Scalar scalar(const Model& model, const std::vector<Vec3>& x, size_t k) {
  const Spring& s = model.spec().springs[k];
  const Vec3 delta = x[size_t(s.j)] - x[size_t(s.i)];
  const double l = delta.norm();
  Scalar out;
  out.direction = l > 0;
  const Vec3 f = (model.spring_kappa[k] * (l - s.rest_length) / l) * delta;
  for (int c = 0; c < 3; ++c) out.force[c] = f[c];
  const double d[3] = {delta[0] / l, delta[1] / l, delta[2] / l};
  const double ratio = s.rest_length / l;
  const double tension = 1.0 - ratio;
  spring_tangent_block(model.spring_kappa[k], tension, ratio, d, out.block);
  out.compressed = tension < 0;
  for (int r = 0; r < 3; ++r)
    out.off[r] = ((std::abs(out.block[sym3(r, 0)]) + std::abs(out.block[sym3(r, 1)])) +
                  std::abs(out.block[sym3(r, 2)])) *
                 model.spring_weight[k];
  return out;
}

TEST(SpringBatch, EveryColumnHasTheScalarFormulasBits) {
  const test::BatchMesh m = test::batch_mesh();
  const SpringBatchInput in = spring_batch_input(m.model, m.x);
  const size_t ns = m.model.spec().springs.size();
  int compressed = 0, undirected = 0;
  SpringBatch b;
  for (size_t first = 0; first < ns; first += kSpringBatch) {
    const size_t count = std::min(kSpringBatch, ns - first);
    spring_batch_generic::compute(in, first, count, true, true, b);
    for (size_t q = 0; q < count; ++q) {
      const Scalar want = scalar(m.model, m.x, first + q);
      SCOPED_TRACE("spring " + std::to_string(first + q));
      ASSERT_EQ(bool(b.direction[q]), want.direction);
      if (!want.direction) {
        ++undirected;
        continue;
      }
      compressed += want.compressed;
      ASSERT_EQ(bool(b.compressed[q]), want.compressed);
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(same(b.force[c][q], want.force[c])) << c;
      for (int c = 0; c < 6; ++c) ASSERT_TRUE(same(b.block[c][q], want.block[c])) << c;
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(same(b.off[c][q], want.off[c])) << c;
    }
  }
  // Spring 0 (zero length) and every spring at the NaN node.
  EXPECT_GE(undirected, 2);
  EXPECT_FALSE(scalar(m.model, m.x, 0).direction);
  EXPECT_FALSE(scalar(m.model, m.x, 5).direction);
  EXPECT_GT(compressed, 100);
}

TEST(SpringBatch, AnyLengthAndOffsetGivesTheSameColumns) {
  // A batch's columns depend on its springs only, not on where it starts or how long it is
  // (short batches fill their last vector with repeats that must not leak).
  const test::BatchMesh m = test::batch_mesh();
  const SpringBatchInput in = spring_batch_input(m.model, m.x);
  SpringBatch whole, part;
  spring_batch_generic::compute(in, 100, kSpringBatch, true, true, whole);
  for (size_t offset : {size_t(0), size_t(1), size_t(3), size_t(7)}) {
    for (size_t count = 1; offset + count <= kSpringBatch; count += 5) {
      spring_batch_generic::compute(in, 100 + offset, count, true, true, part);
      for (size_t q = 0; q < count; ++q) {
        ASSERT_EQ(part.direction[q], whole.direction[offset + q]);
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(same(part.force[c][q], whole.force[c][offset + q]));
        for (int c = 0; c < 6; ++c) ASSERT_TRUE(same(part.block[c][q], whole.block[c][offset + q]));
      }
    }
  }
}

TEST(SpringBatch, ForcesAloneAndBlocksAloneAreTheColumnsOfBoth) {
  const test::BatchMesh m = test::batch_mesh();
  const SpringBatchInput in = spring_batch_input(m.model, m.x);
  SpringBatch both, forces, blocks;
  spring_batch_generic::compute(in, 0, kSpringBatch, true, true, both);
  spring_batch_generic::compute(in, 0, kSpringBatch, true, false, forces);
  spring_batch_generic::compute(in, 0, kSpringBatch, false, true, blocks);
  for (size_t q = 0; q < kSpringBatch; ++q) {
    if (!both.direction[q]) continue;
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(same(forces.force[c][q], both.force[c][q]));
    for (int c = 0; c < 6; ++c) EXPECT_TRUE(same(blocks.block[c][q], both.block[c][q]));
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(same(blocks.off[c][q], both.off[c][q]));
    EXPECT_EQ(blocks.compressed[q], both.compressed[q]);
  }
}

TEST(SpringBatch, PicksTheCopyThisCpuRuns) {
  EXPECT_EQ(spring_batch_for(StepIsa::generic), &spring_batch_generic::compute);
#if defined(__x86_64__)
  if (step_isa_supported(StepIsa::avx2))
    EXPECT_EQ(spring_batch_for(StepIsa::avx2), &spring_batch_avx2::compute);
  else
    EXPECT_EQ(spring_batch_for(StepIsa::avx2), &spring_batch_generic::compute);
#endif
  EXPECT_EQ(spring_batch_for(StepIsa::best), spring_batch_for(best_step_isa()));
}

}  // namespace
}  // namespace dampbound::detail
