// Tests of core/analysis/detail/shifted_cholesky: factor(sigma) succeeds exactly when
// sigma I - A is positive definite, proved_above() is a certified upper bound on lambda_max
// just above the shift, solves match the dense inverse, the budget stops the analysis, and
// assign() keeps or renews the pattern; against Eigen's dense solvers.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/shifted_cholesky.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "dampbound/analysis/linear_stability.hpp"
#include "tests/core/analysis/detail/factor_matrices.hpp"

namespace dampbound::detail {
namespace {

double dense_lambda_max(const SparseMatrix& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(A), Eigen::EigenvaluesOnly);
  return es.eigenvalues()(A.rows() - 1);
}

TEST(ShiftedCholesky, FactorsExactlyAboveTheTopEigenvalueAndProvesABoundJustAboveTheShift) {
  for (const SparseMatrix& A : {test::deformed_plane(8), test::block(3)}) {
    const double top = dense_lambda_max(A);
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
  const double sigma = 1.01 * dense_lambda_max(A);
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
  EXPECT_TRUE(g.factor(1.01 * dense_lambda_max(A)));
}

TEST(ShiftedCholesky, AssignTakesNewValuesOfTheSamePatternOrAnotherPattern) {
  const SparseMatrix A = test::deformed_plane(8);
  ShiftedCholesky f(A);
  ASSERT_TRUE(f.factor(1.01 * dense_lambda_max(A)));
  // The same pattern, values doubled: the top doubles.
  const SparseMatrix twice = 2 * A;
  f.assign(twice);
  EXPECT_FALSE(f.ready());
  EXPECT_FALSE(f.factor(1.5 * dense_lambda_max(A)));
  ASSERT_TRUE(f.factor(2.02 * dense_lambda_max(A)));
  EXPECT_GT(f.proved_above(), dense_lambda_max(twice));
  // Another pattern (and size).
  const SparseMatrix B = test::block(3);
  f.assign(B);
  EXPECT_EQ(f.size(), B.rows());
  EXPECT_FALSE(f.factor(0.99 * dense_lambda_max(B)));
  ASSERT_TRUE(f.factor(1.01 * dense_lambda_max(B)));
  EXPECT_GT(f.proved_above(), dense_lambda_max(B));
}

TEST(ShiftedCholesky, RowsAloneStayOutOfTheFactorisationAndKeepEveryAnswer) {
  // A flat plane at rest: its out-of-plane rows hold the anchors' diagonal entries alone.
  const Model m = compile_model(make_grid(GridSpec{9, 9, 0.57, true, true}), Params{});
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, m.spec().rest));
  const double top = dense_lambda_max(A);
  // The rows with no entry off the diagonal: one of each node's three, out of the plane.
  double lone_top = 0;
  Eigen::Index lone = 0;
  for (Eigen::Index k = 0; k < A.rows(); ++k) {
    int off = 0;
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) off += it.row() != k;
    if (off == 0) lone_top = std::max(lone_top, A.coeff(k, k)), ++lone;
  }
  ASSERT_EQ(lone, A.rows() / 3);
  ShiftedCholesky f(A);
  EXPECT_EQ(f.size(), A.rows());
  EXPECT_EQ(f.factored_rows(), A.rows() - lone);
  EXPECT_FALSE(f.factor(top * (1 - 1e-6)));
  const double sigma = top * (1 + 1e-6);
  ASSERT_TRUE(f.factor(sigma));
  EXPECT_GT(f.proved_above(), top);
  EXPECT_LT(f.proved_above() - sigma, 1e-9 * top);
  // Below the lone rows' largest entry: they fail it (exactly there: sigma = that entry).
  ASSERT_LT(lone_top, top);
  ASSERT_GT(lone_top, 0);
  EXPECT_FALSE(f.factor(lone_top));
  // Solves match the dense inverse on every row, in place too.
  ASSERT_TRUE(f.factor(sigma));
  const Eigen::Index n = A.rows();
  const Eigen::MatrixXd S = sigma * Eigen::MatrixXd::Identity(n, n) - Eigen::MatrixXd(A);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1, 2).array().cos();
  const Eigen::VectorXd expected = S.ldlt().solve(b);
  Eigen::VectorXd x(n), in_place = b;
  f.solve(b.data(), x.data());
  f.solve(in_place.data(), in_place.data());
  EXPECT_LT((x - expected).norm(), 1e-10 * expected.norm());
  EXPECT_EQ(x, in_place);
  // A diagonal matrix: every row alone, nothing for CHOLMOD.
  const SparseMatrix D = (Eigen::VectorXd::LinSpaced(30, 1, 3)).asDiagonal().toDenseMatrix().sparseView();
  ShiftedCholesky g(D);
  EXPECT_EQ(g.factored_rows(), 0);
  EXPECT_FALSE(g.factor(3));
  ASSERT_TRUE(g.factor(std::nextafter(3.0, 4.0)));
  EXPECT_GT(g.proved_above(), 3);
}

}  // namespace
}  // namespace dampbound::detail
