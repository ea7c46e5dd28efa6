// Tests of core/analysis/detail/definite_root: the largest x with 4 I - S(x) proved positive
// definite, for a damping coefficient (S linear) and for dt (S quadratic), against the dense
// generalised eigenvalue and a dense bisection on a tetrahedral block with non-uniform
// damping; the bracket's width, the few factorisations, and the ends (never stable, never
// unstable).
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/definite_root.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "tests/core/analysis/detail/factor_matrices.hpp"

namespace dampbound::detail {
namespace {

double dense_top(const SparseMatrix& S) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(S), Eigen::EigenvaluesOnly);
  return es.eigenvalues()(S.rows() - 1);
}

/// A (the block's M^-1/2 K M^-1/2, top scaled to 1) and a diagonal G of rates in [0.5, 2].
struct Mats {
  SparseMatrix A, G;
};
Mats mats() {
  Mats m;
  m.A = test::block(5);
  m.A /= dense_top(m.A);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  m.G.resize(m.A.rows(), m.A.cols());
  for (Eigen::Index i = 0; i < m.A.rows(); ++i) m.G.insert(i, i) = u(rng);
  m.G.makeCompressed();
  return m;
}

TEST(DefiniteRoot, LinearFamilyMatchesTheDenseGeneralisedEigenvalue) {
  const Mats m = mats();
  const double h = 1.2;
  const SparseMatrix base = (h * h) * m.A + (2 * h * 0.1) * m.G, step = (2 * h) * m.G;
  IndexFamily family;
  family.S = [&](double v) -> SparseMatrix { return base + v * step; };
  family.D = [&](double) -> SparseMatrix { return step; };
  const DefiniteRoot r = definite_root(family, 0);
  // v* = 1 / theta_max of step u = theta (4 I - base) u.
  const Eigen::Index n = base.rows();
  const Eigen::MatrixXd B0 = 4 * Eigen::MatrixXd::Identity(n, n) - Eigen::MatrixXd(base);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(step), B0,
                                                              Eigen::EigenvaluesOnly);
  const double root = 1 / es.eigenvalues()(n - 1);
  EXPECT_LT(r.stable, root * (1 + 1e-12));
  EXPECT_GT(r.stable, root * (1 - 2e-10));
  EXPECT_GT(r.unstable, r.stable);
  EXPECT_LE(r.unstable - r.stable, 1e-10 * r.unstable);
  EXPECT_LT(dense_top(base + r.stable * step), 4);
  EXPECT_LE(r.factorizations, 6);
}

TEST(DefiniteRoot, AStartOnTheTopVectorSettlesInAFewSolves) {
  // IndexFamily::start on the top vector of B^-1 D (what SPEC 10's searches get from the
  // certified index): the first Lanczos run settles at once (its Ritz value stays put while
  // the residual sits at its rounding floor), and the search proves the same root.
  const Mats m = mats();
  const double h = 1.2;
  const SparseMatrix base = (h * h) * m.A + (2 * h * 0.1) * m.G, step = (2 * h) * m.G;
  IndexFamily family;
  family.S = [&](double v) -> SparseMatrix { return base + v * step; };
  family.D = [&](double) -> SparseMatrix { return step; };
  const DefiniteRoot plain = definite_root(family, 0);
  const Eigen::Index n = base.rows();
  const Eigen::MatrixXd B0 = 4 * Eigen::MatrixXd::Identity(n, n) - Eigen::MatrixXd(base);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(step), B0);
  family.start = es.eigenvectors().col(n - 1).normalized();
  const DefiniteRoot started = definite_root(family, 0);
  EXPECT_LE(std::abs(started.stable - plain.stable), 1e-10 * plain.unstable);
  EXPECT_LE(started.unstable - started.stable, 1e-10 * started.unstable);
  EXPECT_LT(dense_top(base + started.stable * step), 4);
  EXPECT_LE(started.solves, 4) << "from Lanczos's usual start: " << plain.solves;
  EXPECT_LT(started.solves, plain.solves);
  EXPECT_LE(started.factorizations, 3);
}

/// The index in dt, S(h) = h^2 A + 2 h C, with C = 0.3 G + 0.05 A.
struct DtFamily {
  Mats m = mats();
  SparseMatrix C = 0.3 * m.G + 0.05 * m.A;
  IndexFamily family;
  DtFamily() {
    family.S = [this](double h) -> SparseMatrix { return (h * h) * m.A + (2 * h) * C; };
    family.D = [this](double h) -> SparseMatrix { return (2 * h) * m.A + 2.0 * C; };
    family.Q = m.A;
  }
  DtFamily(const DtFamily&) = delete;
  DtFamily& operator=(const DtFamily&) = delete;
};

TEST(DefiniteRoot, QuadraticFamilyMatchesADenseBisectionInDt) {
  const DtFamily dt;
  const IndexFamily& family = dt.family;
  double lo = 0.5, hi = 3;  // the dense root, bisected to 1e-13
  for (int k = 0; k < 45; ++k) {
    const double mid = 0.5 * (lo + hi);
    (dense_top(family.S(mid)) < 4 ? lo : hi) = mid;
  }
  for (const double from : {0.5, 3.0}) {  // from a stable dt, and from one past the limit
    const DefiniteRoot r = definite_root(family, from);
    EXPECT_LT(r.stable, hi * (1 + 1e-12)) << from;
    EXPECT_GT(r.stable, lo * (1 - 2e-10)) << from;
    EXPECT_LE(r.unstable - r.stable, 1e-10 * r.unstable) << from;
    EXPECT_LE(r.factorizations, from < 1 ? 6 : 9) << from;
  }
}

TEST(DefiniteRoot, FromJustBelowTheRootItSettlesInAFewFactorisations) {
  // Started within 1e-9 of the root, t is at the rounding noise of u^T B u: the estimate must
  // settle to the digits that place a probe rather than run its twelve rounds and creep up
  // by a width per factorisation.
  const DtFamily dt;
  const IndexFamily& family = dt.family;
  const double root = definite_root(family, 0.5).stable;
  for (const double below : {1e-9, 3e-9, 1e-8}) {
    const DefiniteRoot r = definite_root(family, root * (1 - below));
    EXPECT_NEAR(r.stable, root, 2e-10 * root) << below;
    EXPECT_LE(r.factorizations, 4) << below;
  }
}

TEST(DefiniteRoot, TheEnds) {
  const Mats m = mats();
  IndexFamily family;
  // S(0) already past 4: nothing from 0 is stable.
  family.S = [&](double v) -> SparseMatrix { return 5.0 * m.A + v * m.G; };
  family.D = [&](double) -> SparseMatrix { return m.G; };
  EXPECT_EQ(definite_root(family, 0).stable, 0);
  // A direction that never grows: no limit.
  const SparseMatrix zero(m.A.rows(), m.A.cols());
  family.S = [&](double v) -> SparseMatrix { return 2.0 * m.A + v * zero; };
  family.D = [&](double) -> SparseMatrix { return zero; };
  EXPECT_TRUE(std::isinf(definite_root(family, 0).stable));
}

}  // namespace
}  // namespace dampbound::detail
