// Tests of core/analysis/detail/lanczos: the start vector, the recurrence (T's Ritz values lie
// in A's spectrum and reach its top; S = scale A + diag(d); the same bits on any thread
// count; an invariant subspace stops it), the single-precision recurrence's matrix_error, and
// the estimate's residual, error and step count. Against Eigen's dense solver.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/lanczos.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "core/analysis/detail/tridiagonal.hpp"
#include "tests/core/analysis/detail/factor_matrices.hpp"

namespace dampbound::detail {
namespace {

Eigen::VectorXd dense_values(const Eigen::MatrixXd& S) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues();
}

double top_ritz(const std::vector<double>& alpha, const std::vector<double>& beta) {
  return largest_tridiagonal_eigenvalue(alpha.data(), beta.data(), static_cast<int>(alpha.size()));
}

TEST(Lanczos, TheStartHasUnitNormAndFlipsEveryOtherNode) {
  for (const Eigen::Index n : {1, 2, 3, 7, 12, 301}) {
    const Eigen::VectorXd v = lanczos_start(n);
    ASSERT_EQ(v.size(), n);
    EXPECT_NEAR(v.norm(), 1, 1e-15);
    const Eigen::VectorXd smooth = Eigen::VectorXd::LinSpaced(n, 0.3, 1.7).array().sin();
    for (Eigen::Index i = 0; i < n; ++i) {
      const bool flipped = (i / 3) % 2 == 1;
      EXPECT_GT(v(i) * smooth(i) * (flipped ? -1 : 1), 0) << "n " << n << " i " << i;
    }
  }
}

TEST(Lanczos, RitzValuesLieInTheSpectrumAndReachItsTop) {
  const SparseMatrix A = test::deformed_plane(8);
  const Eigen::Index n = A.rows();
  const Eigen::VectorXd ev = dense_values(Eigen::MatrixXd(A));
  const double top = ev(n - 1), spread = ev(n - 1) - ev(0);
  LanczosRecurrence<double> l(A, 1);
  EXPECT_EQ(l.matrix_error(), 0);
  EXPECT_EQ(l.vector(), lanczos_start(n));
  double previous = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < 60; ++j) {
    ASSERT_TRUE(l.step());
    ASSERT_EQ(l.alpha.size(), static_cast<size_t>(j + 1));
    const double theta = top_ritz(l.alpha, l.beta);
    EXPECT_LE(theta, top + 1e-12 * spread) << j;  // Cauchy interlacing
    EXPECT_GE(theta, previous - 1e-12 * spread) << j;
    previous = theta;
    EXPECT_NEAR(l.vector().norm(), 1, 1e-12);
  }
  EXPECT_NEAR(previous, top, 1e-8 * top);
}

TEST(Lanczos, ScaledAndShiftedMatrixAndTheSameBitsOnAnyThreadCount) {
  const SparseMatrix A = test::deformed_plane(8);
  const Eigen::Index n = A.rows();
  const Eigen::VectorXd d = Eigen::VectorXd::LinSpaced(n, 0, 3).array().square();
  const double scale = 0.25;
  const Eigen::MatrixXd S = scale * Eigen::MatrixXd(A) + Eigen::MatrixXd(d.asDiagonal());
  const double top = dense_values(S)(n - 1);
  LanczosRecurrence<double> one(A, 1, scale, &d), three(A, 3, scale, &d);
  for (int j = 0; j < 80; ++j) {
    ASSERT_TRUE(one.step());
    ASSERT_TRUE(three.step());
  }
  EXPECT_EQ(one.alpha, three.alpha);
  EXPECT_EQ(one.beta, three.beta);
  EXPECT_EQ(one.vector(), three.vector());
  EXPECT_NEAR(top_ritz(one.alpha, one.beta), top, 1e-8 * top);
}

TEST(Lanczos, AnInvariantSubspaceStopsTheRecurrenceWithExactEigenvalues) {
  // A diagonal matrix with two distinct values: the Krylov space has dimension 2, so the
  // second beta is rounding and the two Ritz values are the eigenvalues.
  const Eigen::Index n = 6;
  SparseMatrix A(n, n);
  for (Eigen::Index i = 0; i < n; ++i) A.insert(i, i) = i < 3 ? 1.0 : 5.0;
  A.makeCompressed();
  LanczosRecurrence<double> l(A, 1);
  EXPECT_TRUE(l.step());
  EXPECT_GT(l.beta.back(), 0.1);
  l.step();
  EXPECT_LT(std::abs(l.beta.back()), 1e-14);
  EXPECT_NEAR(top_ritz(l.alpha, l.beta), 5, 1e-14);
  // One row: the start is the eigenvector, beta is exactly 0 and the step says so.
  SparseMatrix one(1, 1);
  one.insert(0, 0) = 7.0;
  one.makeCompressed();
  LanczosRecurrence<double> single(one, 1);
  EXPECT_FALSE(single.step());
  EXPECT_EQ(single.alpha, std::vector<double>{7.0});
  EXPECT_EQ(single.beta, std::vector<double>{0.0});
}

TEST(Lanczos, SinglePrecisionStaysWithinItsMatrixErrorOfTheTop) {
  const SparseMatrix A = test::deformed_plane(8);
  const Eigen::Index n = A.rows();
  const double top = dense_values(Eigen::MatrixXd(A))(n - 1);
  LanczosRecurrence<float> l(A, 1);
  double worst_row = 0;
  for (Eigen::Index c = 0; c < n; ++c) worst_row = std::max(worst_row, A.col(c).cwiseAbs().sum());
  EXPECT_GE(l.matrix_error(), std::ldexp(worst_row, -24));
  EXPECT_LE(l.matrix_error(), 1.01 * std::ldexp(worst_row, -24) + 1e-40);
  const TopEstimate e = lanczos_estimate(l, n, 200, kLanczosCheck, 1e-7);
  EXPECT_EQ(e.matrix_error, l.matrix_error());
  // Some eigenvalue of the recurrence's matrix lies within the residual of theta; that
  // matrix within matrix_error of A (Weyl); and the float recurrence's own rounding.
  EXPECT_LE(e.theta, top + e.matrix_error + 1e-5 * top);
  EXPECT_NEAR(e.theta, top, 1e-5 * top);
  // Beyond float's range: an infinite matrix error.
  SparseMatrix huge = A;
  huge.coeffRef(0, 0) = 1e300;
  EXPECT_TRUE(std::isinf(LanczosRecurrence<float>(huge, 1).matrix_error()));
  EXPECT_THROW(LanczosRecurrence<float>(A, 1, 2.0), std::invalid_argument);
}

TEST(Lanczos, TheEstimateBracketsAnEigenvalueByItsResidualAndStopsOnItsTolerance) {
  const SparseMatrix A = test::deformed_plane(12);
  const Eigen::Index n = A.rows();
  const Eigen::VectorXd ev = dense_values(Eigen::MatrixXd(A));
  const double top = ev(n - 1);
  LanczosRecurrence<double> l(A, 1);
  const TopEstimate e = lanczos_estimate(l, n, kLanczosSteps, 10, 1e-9);
  EXPECT_LE(e.steps, n);
  EXPECT_EQ(e.steps, static_cast<int>(e.alpha.size()));
  EXPECT_LE(e.theta, top * (1 + 1e-12));
  EXPECT_EQ(e.matrix_error, 0);
  const double nearest = (ev.array() - e.theta).abs().minCoeff();
  EXPECT_LE(nearest, e.residual * (1 + 1e-6) + 1e-12 * top);
  // The stop rule: the extrapolated error below the tolerance, and the true one of its order.
  if (e.steps < n) {
    EXPECT_LT(e.error, 1e-9 * std::abs(e.theta));
  }
  EXPECT_LT(top - e.theta, 1e-6 * top);
  // after_step false stops at once; max_steps caps the steps.
  LanczosRecurrence<double> a(A, 1), b(A, 1);
  EXPECT_EQ(lanczos_estimate(a, n, kLanczosSteps, 10, 1e-9, [] { return false; }).steps, 1);
  const TopEstimate short_run = lanczos_estimate(b, n, 7);
  EXPECT_EQ(short_run.steps, 7);
  EXPECT_EQ(short_run.error, short_run.residual);  // too few checkpoints to extrapolate
}

}  // namespace
}  // namespace dampbound::detail
