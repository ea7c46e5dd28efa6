// Tests of core/physics/detail/spring_pass: the forces and SPEC 9's row sums computed in one pass are
// the very bits of each computed alone, on one thread and on several, with fixed nodes,
// compressed springs and a spring of zero length in the mesh; and the counts agree.
#include "core/physics/detail/spring_pass.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>

#include "core/physics/safe_bound.hpp"
#include "dampbound/physics/forces.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound::detail {
namespace {

/// A 12^3 lattice with diagonals (1728 nodes, ~10k springs), every fourth node of one face
/// fixed, varied masses and anchors, shaken so springs stretch and compress; spring 0 is
/// given zero length (its ends on top of each other).
struct Mesh {
  Model model;
  std::vector<Vec3> x;
};

Mesh mesh() {
  Params p;
  Mesh out{compile_model(test::cube_lattice(12, 1.0,
                                            [](ModelSpec& m, int i, int a, int, int) {
                                              m.mass_scale.back() = 1 + (i % 5) * 0.5;
                                              m.anchor_scale.back() = i % 3 == 0 ? 1.5 : 0.0;
                                              m.fixed.back() = a == 0 && i % 4 == 0;
                                            }),
                         p),
           {}};
  out.x = out.model.spec().rest;
  test::shake(out.x, 0.3, 7);
  const Spring& s0 = out.model.spec().springs[0];
  out.x[static_cast<size_t>(s0.j)] = out.x[static_cast<size_t>(s0.i)];
  return out;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(SpringPass, BothAtOnceAreTheBitsOfEachAloneOnAnyThreadCount) {
  const Mesh m = mesh();
  // The references: each output alone, on one thread (the serial scatter loops).
  std::vector<Vec3> force;
  std::vector<double> rows;
  const int zero = internal_forces(m.model, m.x, force);
  const int compressed = safe_row_sums(m.model, m.x, rows);
  ASSERT_EQ(zero, 1);
  ASSERT_GT(compressed, 0);
  for (int threads : {1, 2, 3}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    SpringPass pass;
    pass.threads.set_threads(threads);
    pass.threads.set_grain(500);  // split this small mesh
    std::vector<Vec3> f;
    std::vector<double> r;
    const SpringCounts both = spring_pass(m.model, m.x, &f, &r, &pass);
    EXPECT_EQ(both.zero_length, zero);
    EXPECT_EQ(both.compressed, compressed);
    EXPECT_TRUE(same_bits(f, force));
    EXPECT_TRUE(same_bits(r, rows));
    // Each alone through the same pass object (its buffers resized between layouts).
    std::vector<Vec3> f_alone;
    std::vector<double> r_alone;
    EXPECT_EQ(spring_pass(m.model, m.x, &f_alone, nullptr, &pass).zero_length, zero);
    EXPECT_EQ(spring_pass(m.model, m.x, nullptr, &r_alone, &pass).compressed, compressed);
    EXPECT_TRUE(same_bits(f_alone, force));
    EXPECT_TRUE(same_bits(r_alone, rows));
  }
}

TEST(SpringPass, FixedNodesHaveNoRowsAndTheirColumnsDropOut) {
  const Mesh m = mesh();
  // A vector left over from elsewhere: the pass writes every node's R_i, 0 at fixed nodes.
  std::vector<double> rows(m.x.size() + 5, std::numeric_limits<double>::quiet_NaN());
  spring_pass(m.model, m.x, nullptr, &rows, nullptr);
  ASSERT_EQ(rows.size(), m.x.size());
  int fixed = 0;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (m.model.spec().fixed[i]) {
      ++fixed;
      EXPECT_EQ(rows[i], 0.0) << "node " << i;
    } else {
      EXPECT_GT(rows[i], 0.0) << "node " << i;
    }
  }
  EXPECT_GT(fixed, 0);
}

TEST(SpringPass, NothingAskedNothingWritten) {
  const Mesh m = mesh();
  const SpringCounts c = spring_pass(m.model, m.x, nullptr, nullptr, nullptr);
  EXPECT_EQ(c.zero_length, 1);
  EXPECT_EQ(c.compressed, 0);  // counted only with the row sums
}

}  // namespace
}  // namespace dampbound::detail
