// Tests of core/analysis/detail/shifted_cholesky: factor(sigma) succeeds exactly when
// sigma I - A is positive definite, proved_above() is a certified upper bound on lambda_max
// just above the shift, solves match the dense inverse, the budget stops the analysis, and
// assign() keeps or renews the pattern; against Eigen's dense solvers.
// clang-format off
#include "core/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/shifted_cholesky.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "tests/core/analysis/detail/factor_matrices.hpp"

namespace dampbound::detail {
namespace {

double dense_top(const SparseMatrix& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(A), Eigen::EigenvaluesOnly);
  return es.eigenvalues()(A.rows() - 1);
}

TEST(ShiftedCholesky, FactorsExactlyAboveTheTopEigenvalueAndProvesABoundJustAboveTheShift) {
  for (const SparseMatrix& A : {test::deformed_plane(8), test::block(3)}) {
    const double top = dense_top(A);
    ShiftedCholesky f(A);
    EXPECT_EQ(f.size(), A.rows());
    EXPECT_FALSE(f.factor(top * (1 - 1e-6)));
    EXPECT_FALSE(f.ready());
    EXPECT_FALSE(f.factor(0.5 * top));
    for (const double rel : {1e-6, 1e-3, 0.5}) {
      const double sigma = top * (1 + rel);
      ASSERT_TRUE(f.factor(sigma)) << rel;
      EXPECT_TRUE(f.ready());
      EXPECT_EQ(f.shift(), sigma);
      const double proved = f.proved_above();
      EXPECT_GT(proved, top);
      EXPECT_GE(proved, sigma);
      EXPECT_LT(proved - sigma, 1e-9 * top) << rel;  // the rounding's allowance is small
    }
    EXPECT_EQ(f.factorizations, 5);
  }
}

TEST(ShiftedCholesky, SolvesMatchTheDenseInverseOnOneThreadAndTwo) {
  const SparseMatrix A = test::deformed_plane(10);
  const double sigma = 1.01 * dense_top(A);
  const Eigen::Index n = A.rows();
  const Eigen::MatrixXd S = sigma * Eigen::MatrixXd::Identity(n, n) - Eigen::MatrixXd(A);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1, 2).array().cos();
  const Eigen::VectorXd expected = S.ldlt().solve(b);
  Eigen::VectorXd one(n), two(n);
  ShiftedCholesky f(A);
  ASSERT_TRUE(f.factor(sigma));
  f.set_solve_threads(1);
  f.solve(b.data(), one.data());
  f.set_solve_threads(2);
  f.solve(b.data(), two.data());
  EXPECT_EQ(f.solves, 2);
  EXPECT_LT((one - expected).norm(), 1e-10 * expected.norm());
  EXPECT_EQ(one, two);
}

TEST(ShiftedCholesky, TheAnalysisThrowsOverTheBudgetWithCholmodsPrediction) {
  const SparseMatrix A = test::deformed_plane(8);
  ShiftedCholesky f(A);
  try {
    f.analyse(1);
    FAIL() << "a budget of 1 flop must be exceeded";
  } catch (const FactorisationOverBudget& e) {
    EXPECT_GT(e.flops, 1);
    EXPECT_GT(e.bytes, 0);
    EXPECT_EQ(e.budget, 1);
    EXPECT_FALSE(e.amd_only);
  }
  ShiftedCholesky g(A);
  EXPECT_NO_THROW(g.analyse(kNoFactorBudget));
  EXPECT_TRUE(g.factor(1.01 * dense_top(A)));
}

TEST(ShiftedCholesky, AssignTakesNewValuesOfTheSamePatternOrAnotherPattern) {
  const SparseMatrix A = test::deformed_plane(8);
  ShiftedCholesky f(A);
  ASSERT_TRUE(f.factor(1.01 * dense_top(A)));
  // The same pattern, values doubled: the top doubles.
  const SparseMatrix twice = 2 * A;
  f.assign(twice);
  EXPECT_FALSE(f.ready());
  EXPECT_FALSE(f.factor(1.5 * dense_top(A)));
  ASSERT_TRUE(f.factor(2.02 * dense_top(A)));
  EXPECT_GT(f.proved_above(), dense_top(twice));
  // Another pattern (and size).
  const SparseMatrix B = test::block(3);
  f.assign(B);
  EXPECT_EQ(f.size(), B.rows());
  EXPECT_FALSE(f.factor(0.99 * dense_top(B)));
  ASSERT_TRUE(f.factor(1.01 * dense_top(B)));
  EXPECT_GT(f.proved_above(), dense_top(B));
}

}  // namespace
}  // namespace dampbound::detail
