// Tests of core/analysis/detail/inverse_lanczos: the top eigenvector of (shift I - A)^-1 is
// A's eigenvector of the eigenvalue nearest below the shift, from the short Lanczos and from
// Spectra's; its Rayleigh quotient in A reaches lambda_max to the certificate's width.
// Against Eigen's dense solver.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/inverse_lanczos.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "core/analysis/detail/lanczos.hpp"
#include "tests/core/analysis/detail/factor_matrices.hpp"

namespace dampbound::detail {
namespace {

struct Dense {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
};

Dense dense(const SparseMatrix& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(A)};
  return {es.eigenvalues(), es.eigenvectors()};
}

double rayleigh(const SparseMatrix& A, const Eigen::VectorXd& u) {
  return u.dot(A * u) / u.squaredNorm();
}

/// |cos| of the angle between u and the dense eigenvector k.
double alignment(const Dense& d, Eigen::Index k, const Eigen::VectorXd& u) {
  return std::abs(d.vectors.col(k).dot(u)) / u.norm();
}

TEST(InverseLanczos, TheShortLanczosFindsTheTopEigenvectorWithAShiftJustAboveIt) {
  const SparseMatrix A = test::deformed_plane(12);
  const Dense d = dense(A);
  const Eigen::Index n = A.rows();
  const double top = d.values(n - 1), gap = top - d.values(n - 2);
  ShiftedCholesky f(A);
  ASSERT_TRUE(f.factor(top + 0.01 * gap));
  Eigen::VectorXd u;
  ASSERT_TRUE(short_inverse_lanczos(f, lanczos_start(n), u, kShortTolerance));
  ASSERT_EQ(u.size(), n);
  EXPECT_LE(f.solves, kShortSteps);
  EXPECT_GT(alignment(d, n - 1, u), 1 - 1e-10);
  EXPECT_NEAR(rayleigh(A, u), top, 1e-10 * top);
  EXPECT_LE(rayleigh(A, u), top * (1 + 1e-14));
}

TEST(InverseLanczos, AShortLanczosThatCannotReachItsToleranceLeavesTheVectorUntouched) {
  const SparseMatrix A = test::deformed_plane(12);
  const Dense d = dense(A);
  ShiftedCholesky f(A);
  ASSERT_TRUE(f.factor(2 * d.values(A.rows() - 1)));
  Eigen::VectorXd u = Eigen::VectorXd::Constant(3, 7.0);
  EXPECT_FALSE(short_inverse_lanczos(f, lanczos_start(A.rows()), u, 0.0));
  EXPECT_EQ(f.solves, kShortSteps);
  EXPECT_EQ(u, Eigen::VectorXd::Constant(3, 7.0));
}

TEST(InverseLanczos, SpectrasLanczosFindsTheTopEigenvectorFromItsOwnStartOrAGivenOne) {
  const SparseMatrix A = test::deformed_plane(12);
  const Dense d = dense(A);
  const Eigen::Index n = A.rows();
  const double top = d.values(n - 1);
  {
    ShiftedCholesky f(A);
    ASSERT_TRUE(f.factor(top * 1.001));
    Eigen::VectorXd u;
    inverse_lanczos(f, u, 1e-12);
    ASSERT_EQ(u.size(), n);
    EXPECT_NEAR(rayleigh(A, u), top, 1e-10 * top);
    Eigen::VectorXd v = lanczos_start(n);
    inverse_lanczos(f, v, 1e-12);
    EXPECT_NEAR(rayleigh(A, v), top, 1e-10 * top);
    EXPECT_GT(alignment(d, n - 1, v), 1 - 1e-8);
  }
}

}  // namespace
}  // namespace dampbound::detail
