// Tests of core/analysis/detail/symmetric_product: the threaded passes of a Lanczos step give
// the bits of Eigen's serial `w = A * v; w -= b * p` (and of the scaled, shifted operator, and
// of `w -= a * v`) on random symmetric matrices (duplicates summed, empty rows, signed zeros,
// entries over many magnitudes, an uncompressed matrix) and on an assembled stiffness, their
// sums the documented blocked order on 1 to 3 threads; the single-precision passes the bits of
// their documented float arithmetic on 1 to 3 threads; the single-precision Lanczos estimate
// within its matrix error of the double one; and a certified eigenvalue is the same bits on 1
// and 2 threads.
#include "core/analysis/detail/symmetric_product.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/analysis/detail/lanczos.hpp"
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

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), static_cast<size_t>(a.size()) * sizeof(double)) == 0;
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// The documented order of a step's sums: blocks of `block` rows, four accumulators in each
/// (row index mod 4) combined as (s0 + s1) + (s2 + s3), the blocks added in order.
double blocked_sum(const Eigen::VectorXd& x, const Eigen::VectorXd& y, size_t block) {
  double total = 0;
  for (size_t first = 0; first < static_cast<size_t>(x.size()); first += block) {
    double s[4] = {0, 0, 0, 0};
    for (size_t r = first; r < std::min<size_t>(first + block, x.size()); ++r)
      s[r % 4] += x(static_cast<Eigen::Index>(r)) * y(static_cast<Eigen::Index>(r));
    total += (s[0] + s[1]) + (s[2] + s[3]);
  }
  return total;
}

constexpr size_t kBlock = 16;  // small blocks, so that a few hundred rows split among threads

/// product_and_dot on 1 to 3 threads (S = A, and S = scale A + diag(d)) against Eigen's
/// serial expressions; subtract_and_square and divide after it.
void expect_eigen_bits(const SparseMatrix& A, unsigned seed) {
  ASSERT_TRUE(A.isApprox(SparseMatrix(A.transpose()), 0));  // the test's own premise
  const Eigen::VectorXd v = random_vector(A.rows(), seed), p = random_vector(A.rows(), seed + 1);
  const Eigen::VectorXd d = random_vector(A.rows(), seed + 2);
  for (const Eigen::VectorXd* shift : {static_cast<const Eigen::VectorXd*>(nullptr), &d}) {
    const double scale = shift ? 0.37 : 1.0;
    for (double b : {0.0, 0.73, -2.5e-3}) {
      Eigen::VectorXd expected(A.rows());
      expected.noalias() = A * v;
      if (shift) expected = scale * expected + d.cwiseProduct(v);
      expected -= b * p;
      const double a = 0.61;
      Eigen::VectorXd subtracted = expected;
      subtracted -= a * v;
      for (int threads = 1; threads <= 3; ++threads) {
        SCOPED_TRACE("threads " + std::to_string(threads) + ", b " + std::to_string(b) +
                     (shift ? ", shifted" : ""));
        NodeThreads pool(threads);
        pool.set_grain(1);
        Eigen::VectorXd w, out;
        std::vector<double> partial;
        const double dot = product_and_dot({A, scale, shift}, v, b, p, w, partial, pool, kBlock);
        EXPECT_TRUE(same_bits(w, expected));
        EXPECT_TRUE(same_bits(dot, blocked_sum(expected, v, kBlock)));
        const double squares = subtract_and_square(w, a, v, partial, pool, kBlock);
        EXPECT_TRUE(same_bits(w, subtracted));
        EXPECT_TRUE(same_bits(squares, blocked_sum(subtracted, subtracted, kBlock)));
        divide(w, 3.0, out, pool, kBlock);
        EXPECT_TRUE(same_bits(out, Eigen::VectorXd(subtracted / 3.0)));
      }
    }
  }
}

/// A blocked sum is as accurate as a serial one: x . x of 10^5 terms over many magnitudes (the
/// product with the identity) within 1e-13 of the long double sum, in 25 blocks on 2 threads.
TEST(SymmetricProduct, BlockedSumIsAccurate) {
  const Eigen::Index n = 100000;
  const Eigen::VectorXd x = random_vector(n, 41);
  SparseMatrix I(n, n);
  I.setIdentity();
  long double exact = 0;
  for (Eigen::Index i = 0; i < n; ++i) exact += static_cast<long double>(x(i)) * x(i);
  NodeThreads pool(2);
  Eigen::VectorXd w;
  std::vector<double> partial;
  const double dot = product_and_dot({I}, x, 0.0, x, w, partial, pool);
  EXPECT_EQ(partial.size(), 25u);
  EXPECT_NEAR(dot, static_cast<double>(exact), 1e-13 * static_cast<double>(exact));
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
  std::vector<Vec3> x = model.spec().rest;
  test::shake(x, 0.05, 99);
  expect_eigen_bits(mass_weighted(model, tangent_stiffness(model, x)), 5);
}

/// The single-precision passes against their documented arithmetic, serially: each row of
/// A v summed in float in index order, minus b p in float; the sums of the rows' values
/// multiplied in double, in the blocked order; w -= a v and w / b in float. On 1 to 3 threads.
void expect_single_bits(const SparseMatrix& A, unsigned seed) {
  const Eigen::VectorXf v = random_vector(A.rows(), seed).cast<float>();
  const Eigen::VectorXf p = random_vector(A.rows(), seed + 1).cast<float>();
  std::vector<float> values(static_cast<size_t>(A.nonZeros()));
  for (Eigen::Index c = 0, k = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it)
      values[static_cast<size_t>(k++)] = static_cast<float>(it.value());
  ASSERT_TRUE(A.isCompressed());
  const float b = 0.73f, a = 0.61f;
  Eigen::VectorXf expected(A.rows());
  for (Eigen::Index c = 0, k = 0; c < A.outerSize(); ++c) {
    float sum = 0;
    for (SparseMatrix::InnerIterator it(A, c); it; ++it)
      sum += values[static_cast<size_t>(k++)] * v(it.row());
    expected(c) = sum - b * p(c);
  }
  Eigen::VectorXf subtracted(A.rows());
  for (Eigen::Index i = 0; i < A.rows(); ++i) subtracted(i) = expected(i) - a * v(i);
  const Eigen::VectorXd wide = expected.cast<double>(), narrow_v = v.cast<double>();
  const Eigen::VectorXd wide_s = subtracted.cast<double>();
  for (int threads = 1; threads <= 3; ++threads) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    NodeThreads pool(threads);
    pool.set_grain(1);
    Eigen::VectorXf w, out;
    std::vector<double> partial;
    const double dot =
        product_and_dot(SingleOperator{A, values.data()}, v, b, p, w, partial, pool, kBlock);
    EXPECT_EQ(std::memcmp(w.data(), expected.data(), sizeof(float) * static_cast<size_t>(w.size())),
              0);
    EXPECT_TRUE(same_bits(dot, blocked_sum(wide, narrow_v, kBlock)));
    const double squares = subtract_and_square(w, a, v, partial, pool, kBlock);
    EXPECT_EQ(
        std::memcmp(w.data(), subtracted.data(), sizeof(float) * static_cast<size_t>(w.size())), 0);
    EXPECT_TRUE(same_bits(squares, blocked_sum(wide_s, wide_s, kBlock)));
    divide(w, 3.0f, out, pool, kBlock);
    const Eigen::VectorXf divided = subtracted / 3.0f;
    EXPECT_EQ(
        std::memcmp(out.data(), divided.data(), sizeof(float) * static_cast<size_t>(out.size())),
        0);
  }
}

TEST(SymmetricProduct, SinglePrecisionPassesGiveTheirDocumentedBits) {
  for (unsigned seed : {1u, 2u}) expect_single_bits(random_symmetric(400, 5, seed), 30 + seed);
}

/// The estimate that places the first shift, in single precision: the same bits on 1 and 2
/// threads, its top Ritz value within its matrix error (2^-24 of A's largest absolute row sum)
/// of the double recurrence's after the same 200 steps (in practice 100 times closer). A matrix
/// with an entry beyond float's range gets an infinite matrix error, one below its normal range a
/// finite one.
TEST(SymmetricProduct, SinglePrecisionEstimateLiesWithinItsMatrixErrorOfTheDoubleOne) {
  Params p;
  p.m = p.kappa = 0.001;
  const Model model = compile_model(make_grid(GridSpec{105, 105, 0.57, true, true}), p);
  std::vector<Vec3> x = model.spec().rest;
  test::shake(x, 0.05, 17);
  const SparseMatrix A = mass_weighted(model, tangent_stiffness(model, x));
  ASSERT_GT(A.rows(), 32768);  // two threads take part
  LanczosRecurrence<double> exact(A, 1);
  LanczosRecurrence<float> one(A, 1), two(A, 2);
  const TopEstimate d = lanczos_estimate(exact, A.rows(), 200, 50);
  const TopEstimate f1 = lanczos_estimate(one, A.rows(), d.steps, d.steps);
  const TopEstimate f2 = lanczos_estimate(two, A.rows(), d.steps, d.steps);
  EXPECT_EQ(d.matrix_error, 0);
  double row_max = 0;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    row_max = std::max(row_max, A.col(c).cwiseAbs().sum());
  EXPECT_NEAR(f1.matrix_error, std::ldexp(row_max, -24), 1e-5 * f1.matrix_error);
  EXPECT_TRUE(same_bits(f1.theta, f2.theta));
  EXPECT_EQ(f1.steps, d.steps);
  EXPECT_NEAR(f1.theta, d.theta, f1.matrix_error);
  // Much closer in practice: the rounding errors of a uniform mesh do not add up.
  EXPECT_NEAR(f1.theta, d.theta, 1e-2 * f1.matrix_error + 1e-9 * std::abs(d.theta));

  SparseMatrix huge = A;
  huge.coeffRef(7, 7) = 1e39;
  LanczosRecurrence<float> beyond(huge, 1);
  EXPECT_TRUE(std::isinf(beyond.matrix_error()));
  // Below float's normal range the rounding is absolute (at most 2^-150 an entry), and the
  // bound stays finite: a deformed mesh has such entries where a spring is nearly aligned
  // with an axis.
  SparseMatrix tiny = A;
  tiny.coeffRef(7, 7) += 1e-44;
  LanczosRecurrence<float> below(tiny, 1);
  EXPECT_NEAR(below.matrix_error(), f1.matrix_error, 1e-6 * f1.matrix_error);
  EXPECT_THROW(LanczosRecurrence<float>(A, 1, 2.0), std::invalid_argument);
}

/// Above 32768 rows the Lanczos products run on two threads: the certified interval and the
/// Ritz vector are the same bits as on one (a 105 x 105 paper plane at rest: 33075 rows).
TEST(SymmetricProduct, CertifiedEigenvalueSameOnOneAndTwoThreads) {
  Params p;
  p.m = p.kappa = 0.001;
  const Model model = compile_model(make_grid(GridSpec{105, 105, 0.57, true, true}), p);
  const SparseMatrix A = mass_weighted(model, tangent_stiffness(model, model.spec().rest));
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
