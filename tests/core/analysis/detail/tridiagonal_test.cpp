// Tests of core/analysis/detail/tridiagonal (LAPACK's dstebz and dstein): the largest
// eigenvalue and its unit eigenvector against Eigen's dense solver, on random matrices, on
// Wilkinson's W21+ (pairs of eigenvalues equal to 14 digits), on a T that splits into blocks,
// on the smallest sizes and on entries that are not finite.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/tridiagonal.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <vector>

namespace dampbound::detail {
namespace {

struct Tridiagonal {
  std::vector<double> alpha, beta;
  int m() const { return static_cast<int>(alpha.size()); }
  Eigen::MatrixXd dense() const {
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(m(), m());
    for (int i = 0; i < m(); ++i) {
      T(i, i) = alpha[static_cast<size_t>(i)];
      if (i + 1 < m()) T(i, i + 1) = T(i + 1, i) = beta[static_cast<size_t>(i)];
    }
    return T;
  }
};

Tridiagonal random_tridiagonal(int m, unsigned seed) {
  Tridiagonal t;
  auto next = [&] {
    seed = seed * 1103515245u + 12345u;
    return static_cast<double>((seed >> 8) & 0xffffu) / 65535.0 - 0.5;
  };
  for (int i = 0; i < m; ++i) t.alpha.push_back(10 * next());
  for (int i = 0; i + 1 < m; ++i) t.beta.push_back(3 * next() + 0.01);
  return t;
}

/// Wilkinson's W21+: diagonal |10 - i|, off-diagonal 1; its top two eigenvalues agree to 14
/// digits (10.746194182903...).
Tridiagonal wilkinson() {
  Tridiagonal t;
  for (int i = 0; i < 21; ++i) t.alpha.push_back(std::abs(10.0 - i));
  t.beta.assign(20, 1.0);
  return t;
}

void expect_top_matches_dense(const Tridiagonal& t) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(t.dense());
  const double top = es.eigenvalues()(t.m() - 1);
  const double scale = es.eigenvalues().cwiseAbs().maxCoeff();
  const double theta = largest_tridiagonal_eigenvalue(t.alpha.data(), t.beta.data(), t.m());
  EXPECT_NEAR(theta, top, 1e-13 * scale);
  // The pair: the same value, a unit vector with T y = theta y to rounding, its largest entry
  // positive (dstein's sign).
  const TridiagonalTop pair = tridiagonal_top(t.alpha.data(), t.beta.data(), t.m());
  EXPECT_EQ(pair.value, theta);
  ASSERT_EQ(pair.vector.size(), static_cast<size_t>(t.m()));
  const Eigen::Map<const Eigen::VectorXd> y(pair.vector.data(), t.m());
  EXPECT_NEAR(y.norm(), 1, 1e-14);
  EXPECT_LE((t.dense() * y - theta * y).norm(), 1e-13 * scale);
  Eigen::Index biggest = 0;
  y.cwiseAbs().maxCoeff(&biggest);
  EXPECT_GT(y(biggest), 0);
}

TEST(Tridiagonal, LargestEigenpairMatchesDense) {
  for (int m : {1, 2, 3, 17, 150}) expect_top_matches_dense(random_tridiagonal(m, 11u + static_cast<unsigned>(m)));
  expect_top_matches_dense(wilkinson());
}

TEST(Tridiagonal, LastEigenvectorComponentMatchesDense) {
  // Random matrices have a simple top eigenvalue: the component is that of the dense vector.
  for (int m : {2, 5, 40, 150}) {
    const Tridiagonal t = random_tridiagonal(m, 5u + static_cast<unsigned>(m));
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(t.dense());
    const TridiagonalTop pair = tridiagonal_top(t.alpha.data(), t.beta.data(), m);
    ASSERT_EQ(pair.vector.size(), static_cast<size_t>(m));
    EXPECT_NEAR(std::abs(pair.vector.back()), std::abs(es.eigenvectors()(m - 1, m - 1)), 1e-8);
  }
  // One row (no off-diagonal at all): the entry and the vector (1).
  const double one[1] = {4.0};
  const TridiagonalTop single = tridiagonal_top(one, nullptr, 1);
  EXPECT_EQ(single.value, 4.0);
  EXPECT_EQ(single.vector, std::vector<double>{1.0});
}

TEST(Tridiagonal, NearlyRepeatedTopPair) {
  // W21+'s top pair differs by ~1e-13: inverse iteration returns some unit vector y in the
  // span of the pair's eigenvectors u, w (any orthonormal basis of it, as the dense solver
  // gives), so |y_m| <= sqrt(u_m^2 + w_m^2), and well above zero for this matrix.
  const Tridiagonal t = wilkinson();
  const TridiagonalTop pair = tridiagonal_top(t.alpha.data(), t.beta.data(), t.m());
  EXPECT_NEAR(pair.value, 10.746194182903393, 1e-12);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(t.dense());
  const double u_m = es.eigenvectors()(20, 20), w_m = es.eigenvectors()(20, 19);
  ASSERT_EQ(pair.vector.size(), 21u);
  const double y_m = std::abs(pair.vector.back());
  EXPECT_LE(y_m, std::sqrt(u_m * u_m + w_m * w_m) + 1e-9);
  EXPECT_GT(y_m, 0.0);
}

TEST(Tridiagonal, ATopInAnEarlierBlockHasNoWeightOnTheLastRow) {
  // beta_2 = 0 splits T into rows 0..2 and 3..4; the top (about 5.01) lies in the first block,
  // so its eigenvector is zero on the second, and the Lanczos residual it gives is 0.
  Tridiagonal t;
  t.alpha = {5.0, 1.0, 0.5, 2.0, 1.5};
  t.beta = {0.1, 0.2, 0.0, 0.3};
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(t.dense());
  const TridiagonalTop pair = tridiagonal_top(t.alpha.data(), t.beta.data(), t.m());
  EXPECT_NEAR(pair.value, es.eigenvalues()(4), 1e-14 * 5);
  ASSERT_EQ(pair.vector.size(), 5u);
  EXPECT_EQ(pair.vector[3], 0.0);
  EXPECT_EQ(pair.vector[4], 0.0);
  EXPECT_NEAR(std::abs(pair.vector[0]), std::abs(es.eigenvectors()(0, 4)), 1e-12);
}

TEST(Tridiagonal, AnEntryThatIsNotFiniteGivesNoEigenpair) {
  // What Lanczos in float gives for a matrix entry beyond float's range: the caller falls back
  // to Gershgorin's shift (linear_stability_cholesky.cpp).
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  for (const Tridiagonal& t : {Tridiagonal{{1.0, inf, 2.0}, {0.5, 0.5}},
                               Tridiagonal{{1.0, 2.0, 3.0}, {nan, 0.5}}}) {
    EXPECT_TRUE(std::isnan(largest_tridiagonal_eigenvalue(t.alpha.data(), t.beta.data(), t.m())));
    const TridiagonalTop pair = tridiagonal_top(t.alpha.data(), t.beta.data(), t.m());
    EXPECT_TRUE(std::isnan(pair.value));
    EXPECT_TRUE(pair.vector.empty());
  }
}

}  // namespace
}  // namespace dampbound::detail
