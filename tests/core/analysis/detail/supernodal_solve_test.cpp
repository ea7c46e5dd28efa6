#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// Tests of core/analysis/detail/supernodal_solve: on supernodal factors of mesh matrices (a
// small plane, all of whose supernodes are under the BLAS threshold; a deformed plane, mostly
// single columns, and a tetrahedral block, both with top separators past it), the solve agrees with
// CHOLMOD's own to a few units of rounding and solves the system; it works in place; and it refuses
// a failed factor. The split solve (two halves of the elimination tree at once) covers every
// supernode once with whole subtrees, agrees with CHOLMOD's and gives the same bits on one
// thread and two.
#include <gtest/gtest.h>

#include <Eigen/CholmodSupport>
#include <stdexcept>
#include <vector>

#include "core/analysis/detail/serial_openmp.hpp"
#include "core/analysis/detail/shifted_cholesky.hpp"
#include "core/analysis/detail/supernodal_solve.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/analysis/detail/factor_matrices.hpp"

namespace dampbound::detail {
namespace {

using test::block;
using test::deformed_plane;

/// The widest supernode of a factor, in columns.
int widest_supernode(const cholmod_factor& L) {
  const int* super = static_cast<const int*>(L.super);
  int widest = 0;
  for (size_t s = 0; s < L.nsuper; ++s) widest = std::max(widest, super[s + 1] - super[s]);
  return widest;
}

/// sigma I - A factored with sigma above Gershgorin's bound (positive definite): sigma.
double factor_above_gershgorin(const SparseMatrix& A, SupernodalLLT& llt) {
  const SerialOpenMp
      serial;  // as ShiftedCholesky factors: no libgomp threads (and ThreadSanitizer sees them all)
  const double sigma = 1.01 * gershgorin_bounds(A).hi;
  llt.setShift(sigma);
  llt.compute(SparseMatrix(SparseMatrix(-A).triangularView<Eigen::Lower>()));
  return sigma;
}

/// Solves the factor of factor_above_gershgorin for a fixed right-hand side both ways.
void expect_cholmod_solution(const SparseMatrix& A, int min_widest, int max_widest) {
  SupernodalLLT llt;
  const double sigma = factor_above_gershgorin(A, llt);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const cholmod_factor& L = llt.factor();
  ASSERT_TRUE(L.is_super);
  EXPECT_GE(widest_supernode(L), min_widest);
  EXPECT_LE(widest_supernode(L), max_widest);
  Eigen::VectorXd b(A.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i) b(i) = std::sin(0.37 * static_cast<double>(i)) + 0.1;
  const Eigen::VectorXd expected = llt.solve(b);
  Eigen::VectorXd x(A.rows());
  std::vector<double> work;
  supernodal_solve(L, b.data(), x.data(), work);
  EXPECT_LT((x - expected).norm(), 1e-13 * expected.norm());
  // It solves (sigma I - A) x = b.
  const Eigen::VectorXd residual = sigma * x - A * x - b;
  EXPECT_LT(residual.norm(), 1e-12 * b.norm());
  // In place: the right-hand side overwritten by the solution, the same bits.
  Eigen::VectorXd y = b;
  supernodal_solve(L, y.data(), y.data(), work);
  EXPECT_EQ(y, x);
}

TEST(SupernodalSolve, SmallPlaneAgreesWithCholmod) {
  // Every supernode under the BLAS threshold of 32 columns: the loops alone.
  expect_cholmod_solution(deformed_plane(5), 2, 31);
}

TEST(SupernodalSolve, DeformedPlaneAgreesWithCholmod) {
  // Mostly supernodes of one column, the top separators wider than 32: loops and BLAS.
  expect_cholmod_solution(deformed_plane(30), 32, 1 << 30);
}

TEST(SupernodalSolve, TetrahedralBlockWithWideSupernodesAgreesWithCholmod) {
  // The top separators of a 12^3 block are hundreds of columns: BLAS and the loops both.
  expect_cholmod_solution(block(12), 100, 1 << 30);
}

/// split_supernodes at any size, then the split solve on 1 and 2 threads against CHOLMOD's.
void expect_split_solution(const SparseMatrix& A) {
  SupernodalLLT llt;
  const double sigma = factor_above_gershgorin(A, llt);
  ASSERT_EQ(llt.info(), Eigen::Success);
  const cholmod_factor& L = llt.factor();
  EXPECT_EQ(split_supernodes(L).empty(), L.xsize < kSplitEntries);  // small: serial
  const SolveSplit split = split_supernodes(L, 0);
  ASSERT_FALSE(split.empty());
  // Every supernode once: in the top, or in one bin's run; each run a whole subtree (its
  // supernodes' parents inside it but for its last, whose parent is in the top or none).
  std::vector<int> seen(L.nsuper, 0);
  for (int s : split.top) ++seen[static_cast<size_t>(s)];
  for (const auto& bin : split.bins)
    for (const auto& [from, to] : bin)
      for (int s = from; s <= to; ++s) ++seen[static_cast<size_t>(s)];
  for (size_t s = 0; s < L.nsuper; ++s) EXPECT_EQ(seen[s], 1) << "supernode " << s;
  EXPECT_FALSE(split.bins[0].empty());
  EXPECT_FALSE(split.bins[1].empty());
  Eigen::VectorXd b(A.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i) b(i) = std::cos(0.21 * static_cast<double>(i)) - 0.3;
  const Eigen::VectorXd expected = llt.solve(b);
  std::vector<double> work;
  Eigen::VectorXd one(A.rows()), two(A.rows());
  NodeThreads serial(1), both(2);
  both.set_grain(1);
  supernodal_solve_split(L, split, b.data(), one.data(), work, serial);
  supernodal_solve_split(L, split, b.data(), two.data(), work, both);
  EXPECT_EQ(one, two);
  EXPECT_LT((one - expected).norm(), 1e-13 * expected.norm());
  EXPECT_LT((sigma * one - A * one - b).norm(), 1e-12 * b.norm());
  Eigen::VectorXd y = b;  // in place
  supernodal_solve_split(L, split, y.data(), y.data(), work, both);
  EXPECT_EQ(y, one);
}

TEST(SupernodalSolve, SplitSolveOfAPlaneAgreesWithCholmodOnOneThreadAndTwo) {
  expect_split_solution(deformed_plane(30));
}

TEST(SupernodalSolve, SplitSolveOfATetrahedralBlockAgreesWithCholmodOnOneThreadAndTwo) {
  // Its top separators are hundreds of columns wide: BLAS in the top, loops in the bins.
  expect_split_solution(block(12));
}

TEST(SupernodalSolve, RefusesAFailedFactor) {
  const SparseMatrix A = deformed_plane(12);
  const SparseMatrix B = SparseMatrix(-A).triangularView<Eigen::Lower>();
  SupernodalLLT llt;
  llt.cholmod().print = 0;
  llt.setShift(0.5 * gershgorin_bounds(A).hi);  // below lambda_max: not positive definite
  llt.compute(B);
  ASSERT_NE(llt.info(), Eigen::Success);
  std::vector<double> x(static_cast<size_t>(A.rows())), work;
  EXPECT_THROW(supernodal_solve(llt.factor(), x.data(), x.data(), work), std::invalid_argument);
}

}  // namespace
}  // namespace dampbound::detail
