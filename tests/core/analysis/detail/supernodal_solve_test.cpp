#include "core/analysis/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// Tests of core/analysis/detail/supernodal_solve: on supernodal factors of mesh matrices (a
// small plane, all of whose supernodes are under the BLAS threshold; a deformed plane, mostly
// single columns, and a tetrahedral block, both with top separators past it), the solve agrees with
// CHOLMOD's own to a few units of rounding and solves the system; it works in place; and it refuses
// a failed factor.
#include <gtest/gtest.h>

#include <Eigen/CholmodSupport>
#include <stdexcept>
#include <vector>

#include "core/analysis/detail/shifted_cholesky.hpp"
#include "core/analysis/detail/supernodal_solve.hpp"
#include "core/analysis/linear_stability.hpp"
#include "core/scene.hpp"
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

/// Factors sigma I - A (sigma above Gershgorin's bound: positive definite) and solves it for a
/// fixed right-hand side both ways.
void expect_cholmod_solution(const SparseMatrix& A, int min_widest, int max_widest) {
  const double sigma = 1.01 * gershgorin_bounds(A).hi;
  const SparseMatrix B = SparseMatrix(-A).triangularView<Eigen::Lower>();
  SupernodalLLT llt;
  llt.setShift(sigma);
  llt.compute(B);
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
