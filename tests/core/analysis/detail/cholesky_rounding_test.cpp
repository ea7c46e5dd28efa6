#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// Tests of core/analysis/detail/cholesky_rounding: on factors of mesh matrices (a deformed
// plane, a tetrahedral block, one shifted to within 1e-9 of singular), the bound covers the
// factorisation's actual error ||L L^T - P B~ P^T||_2 plus the diagonal's rounding, and equals
// the formula evaluated on CHOLMOD's own sparse copy of L (so every stored entry of the
// supernodal factor, and nothing above its diagonal blocks, is counted) and the bound of the
// same factor converted to CHOLMOD's simplicial form.
#include <gtest/gtest.h>

#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/analysis/detail/cholesky_rounding.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/analysis/detail/factor_matrices.hpp"

namespace dampbound::detail {
namespace {

class VisibleLLT : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
 public:
  cholmod_factor* factor() { return m_cholmodFactor; }
};

using test::block;
using test::deformed_plane;

/// Factors sigma I - A as the exact analysis does and checks the bound against the error.
void check(const SparseMatrix& A, double sigma) {
  const Eigen::Index n = A.rows();
  const SparseMatrix lower = SparseMatrix(-A).triangularView<Eigen::Lower>();
  VisibleLLT llt;
  llt.setShift(sigma);
  llt.compute(lower);
  ASSERT_EQ(llt.info(), Eigen::Success);
  cholmod_factor& L = *llt.factor();
  ASSERT_TRUE(L.is_super);
  // The matrix as CHOLMOD formed it: the diagonal sigma + (-A_kk) rounded once.
  Eigen::MatrixXd B = -Eigen::MatrixXd(A);
  double diagonal = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    B(k, k) = sigma + B(k, k);
    diagonal = std::max(diagonal, std::abs(B(k, k)));
  }
  const double delta = cholesky_rounding_bound(L, diagonal);

  cholmod_common& c = llt.cholmod();
  // The same factor converted to CHOLMOD's simplicial form gives the same bound.
  cholmod_factor* simplicial = cholmod_copy_factor(&L, &c);
  ASSERT_TRUE(cholmod_change_factor(CHOLMOD_REAL, true, false, true, true, simplicial, &c));
  ASSERT_FALSE(simplicial->is_super);
  EXPECT_NEAR(cholesky_rounding_bound(*simplicial, diagonal), delta, 1e-9 * delta);
  cholmod_free_factor(&simplicial, &c);

  // CHOLMOD's own sparse copy of L (a copy of the factor, converted).
  cholmod_factor* copy = cholmod_copy_factor(&L, &c);
  cholmod_sparse* S = cholmod_factor_to_sparse(copy, &c);
  const int* p = static_cast<const int*>(S->p);
  const int* i = static_cast<const int*>(S->i);
  const double* x = static_cast<const double*>(S->x);
  Eigen::MatrixXd Ld = Eigen::MatrixXd::Zero(n, n);
  std::vector<double> column(static_cast<size_t>(n), 0.0), row(static_cast<size_t>(n), 0.0);
  std::vector<int> entries(static_cast<size_t>(n), 0);
  for (Eigen::Index j = 0; j < n; ++j)
    for (int k = p[j]; k < p[j + 1]; ++k) {
      ASSERT_GE(i[k], j);
      Ld(i[k], j) = x[k];
      column[static_cast<size_t>(j)] += std::abs(x[k]);
      ++entries[static_cast<size_t>(i[k])];
    }
  for (Eigen::Index j = 0; j < n; ++j)
    for (int k = p[j]; k < p[j + 1]; ++k)
      row[static_cast<size_t>(i[k])] += std::abs(x[k]) * column[static_cast<size_t>(j)];
  cholmod_free_sparse(&S, &c);
  cholmod_free_factor(&copy, &c);
  const double u = std::numeric_limits<double>::epsilon() / 2;
  const double m = 2.0 * *std::max_element(entries.begin(), entries.end()) + 4.0;
  const double formula =
      (m * u / (1 - m * u) * *std::max_element(row.begin(), row.end()) + u * diagonal) *
      (1 + 1e-6);
  EXPECT_NEAR(delta, formula, 1e-9 * formula);

  // The actual error of the factorisation, L L^T - P B~ P^T, in long double.
  const int* perm = static_cast<const int*>(L.Perm);
  Eigen::MatrixXd E(n, n);
  for (Eigen::Index r = 0; r < n; ++r)
    for (Eigen::Index s = 0; s <= r; ++s) {
      long double sum = 0;
      for (Eigen::Index k = 0; k <= s; ++k) sum += static_cast<long double>(Ld(r, k)) * Ld(s, k);
      E(r, s) = E(s, r) = static_cast<double>(sum - B(perm[r], perm[s]));
    }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(E, Eigen::EigenvaluesOnly);
  const double error = std::max(std::abs(es.eigenvalues()(0)), std::abs(es.eigenvalues()(n - 1)));
  EXPECT_GT(error, 0);  // a real factorisation, not an exact one
  EXPECT_LE(error + u * diagonal, delta);
  // Small enough for the exact analysis's promised width (~1e-10 relative).
  EXPECT_LT(delta, 1e-11 * diagonal);
}

double largest(const SparseMatrix& A) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(A), Eigen::EigenvaluesOnly);
  return es.eigenvalues()(A.rows() - 1);
}

TEST(CholeskyRounding, CoversTheErrorOfADeformedPlanesFactor) {
  const SparseMatrix A = deformed_plane(12);
  check(A, largest(A) + 0.01);
}

TEST(CholeskyRounding, CoversTheErrorOfABlocksFactor) {
  const SparseMatrix A = block(7);
  check(A, largest(A) + 0.01);
}

TEST(CholeskyRounding, CoversTheErrorOfANearlySingularFactor) {
  const SparseMatrix A = block(7);
  const double top = largest(A);
  check(A, top + 1e-9 * top);
}

}  // namespace
}  // namespace dampbound::detail
