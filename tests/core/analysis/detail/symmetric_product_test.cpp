// Tests of core/analysis/detail/symmetric_product: the threaded Lanczos product gives the bits
// of Eigen's serial `w = A * v; w -= b * p` on random symmetric matrices (duplicates summed,
// empty rows, signed zeros, entries over many magnitudes, an uncompressed matrix) and on an
// assembled stiffness, on 1 to 3 threads; and a certified eigenvalue is the same bits on 1 and
// 2 threads.
#include "core/analysis/detail/symmetric_product.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "core/analysis/linear_stability_cholesky.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound::detail {
namespace {

struct Random {
  unsigned seed;
  double next() {  // in [-0.5, 0.5]
    seed = seed * 1103515245u + 12345u;
    return static_cast<double>((seed >> 8) & 0xffffu) / 65535.0 - 0.5;
  }
};

/// A symmetric n x n matrix: about `per_row` off-diagonal pairs per row (some repeated, so
/// setFromTriplets sums duplicates), every 7th row empty, magnitudes from 1e-8 to 1e8.
SparseMatrix random_symmetric(int n, int per_row, unsigned seed) {
  Random r{seed};
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    if (i % 7 == 3) continue;
    t.emplace_back(i, i, r.next() * std::pow(10.0, 16 * (r.next() + 0.5) - 8));
    for (int e = 0; e < per_row; ++e) {
      int j = static_cast<int>((r.next() + 0.5) * (n - 1));
      if (j % 7 == 3) j = (j + 1) % n;
      const double value = r.next() * std::pow(10.0, 16 * (r.next() + 0.5) - 8);
      t.emplace_back(i, j, value);
      t.emplace_back(j, i, value);
    }
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  Random r{seed};
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v(i) = r.next() * std::pow(10.0, 6 * r.next());
  v(0) = -0.0;
  return v;
}

Eigen::VectorXd eigen_product(const SparseMatrix& A, const Eigen::VectorXd& v, double b,
                              const Eigen::VectorXd& p) {
  Eigen::VectorXd w(A.rows());
  w.noalias() = A * v;
  w -= b * p;
  return w;
}

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), static_cast<size_t>(a.size()) * sizeof(double)) == 0;
}

void expect_eigen_bits(const SparseMatrix& A, unsigned seed) {
  ASSERT_TRUE(A.isApprox(SparseMatrix(A.transpose()), 0));  // the test's own premise
  const Eigen::VectorXd v = random_vector(A.rows(), seed), p = random_vector(A.rows(), seed + 1);
  for (double b : {0.0, 0.73, -2.5e-3}) {
    const Eigen::VectorXd expected = eigen_product(A, v, b, p);
    for (int threads = 1; threads <= 3; ++threads) {
      NodeThreads pool(threads);
      pool.set_grain(16);
      Eigen::VectorXd w;
      symmetric_product(A, v, b, p, w, pool);
      EXPECT_TRUE(same_bits(w, expected)) << "threads " << threads << ", b " << b;
    }
  }
}

TEST(SymmetricProduct, RandomMatricesGiveEigensBits) {
  for (unsigned seed : {1u, 2u, 3u}) expect_eigen_bits(random_symmetric(400, 5, seed), 10 + seed);
}

TEST(SymmetricProduct, UncompressedMatrixGivesEigensBits) {
  SparseMatrix A = random_symmetric(200, 3, 7);
  A.uncompress();
  A.coeffRef(5, 9) += 0.125;  // insertions into an uncompressed matrix leave gaps in its rows
  A.coeffRef(9, 5) += 0.125;
  ASSERT_FALSE(A.isCompressed());
  expect_eigen_bits(A, 21);
}

TEST(SymmetricProduct, AssembledStiffnessGivesEigensBits) {
  Params p;
  p.m = p.kappa = 0.001;
  const Model model = compile_model(test::cube_lattice(6, 0.57, [](ModelSpec& m, int i, int a, int, int) {
    if (a == 0) m.fixed[static_cast<size_t>(i)] = 1;
  }), p);
  std::vector<Vec3> x = model.rest;
  test::shake(x, 0.05, 99);
  expect_eigen_bits(mass_weighted(model, tangent_stiffness(model, x)), 5);
}

/// Above 32768 rows the Lanczos products run on two threads: the certified interval and the
/// Ritz vector are the same bits as on one (a 105 x 105 paper plane at rest: 33075 rows).
TEST(SymmetricProduct, CertifiedEigenvalueSameOnOneAndTwoThreads) {
  Params p;
  p.m = p.kappa = 0.001;
  const Model model = compile_model(make_grid(GridSpec{105, 105, 0.57, true, true}), p);
  const SparseMatrix A = mass_weighted(model, tangent_stiffness(model, model.rest));
  ASSERT_GT(A.rows(), 32768);
  Eigen::VectorXd u1, u2;
  const EigenInterval one = certified_largest_eigenvalue(A, &u1, 1);
  const EigenInterval two = certified_largest_eigenvalue(A, &u2, 2);
  EXPECT_GT(one.lanczos_steps, 0);
  EXPECT_EQ(std::memcmp(&one.lo, &two.lo, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&one.hi, &two.hi, sizeof(double)), 0);
  EXPECT_EQ(one.lanczos_steps, two.lanczos_steps);
  EXPECT_EQ(one.solves, two.solves);
  EXPECT_TRUE(same_bits(u1, u2));
}

}  // namespace
}  // namespace dampbound::detail
