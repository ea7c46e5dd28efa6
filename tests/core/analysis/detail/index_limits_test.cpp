// Tests of core/analysis/detail/index_limits: the paper's step at non-uniform nodal rates,
// its certified index at the scene and its roots in gamma and dt, against dense eigenvalues
// of the index matrix h^2 A + 2 h gamma diag(R) on a tetrahedral block.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/index_limits.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <memory>
#include <random>

#include "core/analysis/detail/shifted_cholesky.hpp"
#include "tests/core/analysis/detail/factor_matrices.hpp"

namespace dampbound::detail {
namespace {

double dense_index(const SparseMatrix& A, const Eigen::VectorXd& R, double gamma, double h) {
  Eigen::MatrixXd S = (h * h) * Eigen::MatrixXd(A);
  S.diagonal() += (2 * h * gamma) * R;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S, Eigen::EigenvaluesOnly);
  return es.eigenvalues()(S.rows() - 1);
}

struct Case {
  ExactInputs in;
  Params params;
  ExactStability e;
};

/// The block's A (top scaled to 1), rates in [0.5, 2], gamma and h stable, and the spectrum's
/// top as the exact route would have certified it.
Case block_case() {
  Case c;
  c.in.A = test::block(5);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(c.in.A),
                                                    Eigen::EigenvaluesOnly);
  const double top = es.eigenvalues()(c.in.A.rows() - 1);
  c.in.A /= top;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  c.in.R.resize(c.in.A.rows());
  for (Eigen::Index i = 0; i < c.in.R.size(); ++i) c.in.R(i) = u(rng);
  c.in.r_min = c.in.R.minCoeff();
  c.in.r_max = c.in.R.maxCoeff();
  c.params.gamma = 0.2;
  c.params.dt = 1.2;
  c.e.spectrum = {es.eigenvalues()(0) / top, 1.0};
  c.e.lambda_max_lo = 1.0;
  return c;
}

TEST(IndexLimits, TheIndexAndItsRootsAreTheDenseOnes) {
  Case c = block_case();
  std::unique_ptr<ShiftedCholesky> factors;
  symmetric_index_limits(c.in, c.params, ExactOptions{}, c.e, factors);
  const double h = c.params.dt, gamma = c.params.gamma;
  EXPECT_EQ(c.e.method, ExactMethod::symmetric_index);
  // The certified index: an upper end within 1e-9 of the dense top.
  const double index = dense_index(c.in.A, c.in.R, gamma, h);
  EXPECT_GE(c.e.index, index);
  EXPECT_LE(c.e.index, index * (1 + 1e-9));
  EXPECT_EQ(c.e.stable, index < 4);
  // Each root: proved stable (dense index below 4) and within 1e-9 of where it reaches 4.
  EXPECT_LT(dense_index(c.in.A, c.in.R, c.e.gamma_hi, h), 4);
  EXPECT_GT(dense_index(c.in.A, c.in.R, c.e.gamma_hi * (1 + 1e-9), h), 4);
  EXPECT_LT(dense_index(c.in.A, c.in.R, gamma, c.e.dt_max), 4);
  EXPECT_GT(dense_index(c.in.A, c.in.R, gamma, c.e.dt_max * (1 + 1e-9)), 4);
  // One pattern analysis for the index and both searches.
  ASSERT_TRUE(factors);
  EXPECT_LE(factors->factorizations, 12);
}

TEST(IndexLimits, AnIndefiniteKKeepsItsLimitsAndGetsTheIndexAlone) {
  Case c = block_case();
  c.e.indefinite = true;
  c.e.gamma_hi = c.e.dt_max = 0;
  std::unique_ptr<ShiftedCholesky> factors;
  symmetric_index_limits(c.in, c.params, ExactOptions{}, c.e, factors);
  EXPECT_EQ(c.e.gamma_hi, 0);
  EXPECT_EQ(c.e.dt_max, 0);
  EXPECT_GE(c.e.index, dense_index(c.in.A, c.in.R, c.params.gamma, c.params.dt));
}

}  // namespace
}  // namespace dampbound::detail
