// Tests of core/analysis/detail/tridiagonal: Sturm counts, the largest eigenvalue and the last
// component of its eigenvector against Eigen's dense solver, on random matrices, on
// Wilkinson's W21+ (pairs of eigenvalues equal to 14 digits) and on the smallest sizes.
// clang-format off
#include "core/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/tridiagonal.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
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
  // Counts on either side of every eigenvalue.
  for (int k = 0; k < t.m(); ++k) {
    const double ev = es.eigenvalues()(k);
    const double gap_below = k > 0 ? ev - es.eigenvalues()(k - 1) : 1.0;
    if (gap_below < 1e-9 * scale) continue;  // an equal pair: no point between them
    EXPECT_EQ(eigenvalues_below(t.alpha.data(), t.beta.data(), t.m(), ev - 0.5 * gap_below), k);
  }
  EXPECT_EQ(eigenvalues_below(t.alpha.data(), t.beta.data(), t.m(), top + 1e-9 * scale), t.m());
}

TEST(Tridiagonal, LargestEigenvalueAndCountsMatchDense) {
  for (int m : {1, 2, 3, 17, 150}) expect_top_matches_dense(random_tridiagonal(m, 11u + static_cast<unsigned>(m)));
  expect_top_matches_dense(wilkinson());
}

TEST(Tridiagonal, LastEigenvectorComponentMatchesDense) {
  // Random matrices have a simple top eigenvalue: the component is that of the dense vector.
  for (int m : {2, 5, 40, 150}) {
    const Tridiagonal t = random_tridiagonal(m, 5u + static_cast<unsigned>(m));
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(t.dense());
    const double theta = largest_tridiagonal_eigenvalue(t.alpha.data(), t.beta.data(), m);
    EXPECT_NEAR(last_eigenvector_component(t.alpha.data(), t.beta.data(), m, theta),
                std::abs(es.eigenvectors()(m - 1, m - 1)), 1e-8);
  }
  const double one[1] = {4.0};
  EXPECT_EQ(last_eigenvector_component(one, nullptr, 1, 4.0), 1.0);
}

TEST(Tridiagonal, NearlyRepeatedTopPair) {
  // W21+'s top pair differs by ~1e-13: inverse iteration returns some unit vector y in the
  // span of the pair's eigenvectors u, w (any orthonormal basis of it, as the dense solver
  // gives), so |y_m| <= sqrt(u_m^2 + w_m^2), and well above zero for this matrix.
  const Tridiagonal t = wilkinson();
  const double theta = largest_tridiagonal_eigenvalue(t.alpha.data(), t.beta.data(), t.m());
  EXPECT_NEAR(theta, 10.746194182903393, 1e-12);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(t.dense());
  const double u_m = es.eigenvectors()(20, 20), w_m = es.eigenvectors()(20, 19);
  const double y_m = last_eigenvector_component(t.alpha.data(), t.beta.data(), t.m(), theta);
  EXPECT_LE(y_m, std::sqrt(u_m * u_m + w_m * w_m) + 1e-9);
  EXPECT_GT(y_m, 0.0);
}

}  // namespace
}  // namespace dampbound::detail
