#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// Tests of core/linear_stability_cholesky: Gershgorin's bounds (SPEC 9's R_i on the paper
// plane), certified intervals that enclose the dense eigenvalues (meshes at rest and deformed,
// a clustered top, a matrix with negative eigenvalues), and their width; a proved floor that
// gives the smallest eigenvalue without factorising, and one that is too low to; calls from two
// threads at once.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bench/bench_meshes.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

Eigen::VectorXd dense_eigenvalues(const SparseMatrix& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(A), Eigen::EigenvaluesOnly};
  return es.eigenvalues();
}

/// An n x n plane at m = 0.002, kappa = 0.05 (anchors, diagonals).
Model plane_model(int n) {
  Params p;
  p.m = 0.002;
  p.kappa = 0.05;
  return compile_model(make_grid(GridSpec{n, n, 0.57, true, true}), p);
}

SparseMatrix plane_matrix(int n, double deform) {
  const Model m = plane_model(n);
  std::vector<Vec3> x = m.spec().rest;
  test::shake(x, deform, 3);
  return mass_weighted(m, tangent_stiffness(m, x));
}

/// Checks lo <= lambda <= hi and the width promised in the header.
void expect_encloses(const EigenInterval& r, double lambda, double scale) {
  EXPECT_LE(r.lo, lambda + 1e-13 * scale);
  EXPECT_GE(r.hi, lambda);
  EXPECT_LE(r.hi - r.lo, 1e-10 * std::abs(lambda) + 2e-11 * scale + 1e-11 * scale);
}

TEST(Gershgorin, PaperPlaneRowSumsAreSpec9sBound) {
  // SPEC 9: an interior node of the paper plane has R_i = 9 kappa/m, the largest of all.
  Params p;
  p.m = 0.001;
  p.kappa = 0.001;
  const Model m = compile_model(make_grid(GridSpec{12, 12, 0.57, true, true}), p);
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, m.spec().rest));
  const GershgorinBounds g = gershgorin_bounds(A);
  EXPECT_NEAR(g.hi, 9.0, 1e-12);
  const Eigen::VectorXd ev = dense_eigenvalues(A);
  EXPECT_LE(ev.maxCoeff(), g.hi);
  EXPECT_GE(ev.minCoeff(), g.lo);
}

TEST(CertifiedEigenvalue, EnclosesTheDenseEigenvaluesOfMeshes) {
  for (double deform : {0.0, 0.2}) {
    const SparseMatrix A = plane_matrix(12, deform);
    const Eigen::VectorXd ev = dense_eigenvalues(A);
    const GershgorinBounds g = gershgorin_bounds(A);
    const double scale = g.hi - g.lo;
    Eigen::VectorXd u;
    const EigenInterval top = certified_largest_eigenvalue(A, &u);
    expect_encloses(top, ev.maxCoeff(), scale);
    EXPECT_NEAR(u.norm(), 1.0, 1e-12);
    EXPECT_GE(top.factorizations, 2);  // Gershgorin's shift, then at least one closer
    const EigenInterval bottom = certified_smallest_eigenvalue(A);
    expect_encloses(bottom, ev.minCoeff(), scale);
  }
}

TEST(CertifiedEigenvalue, ClusteredTopAndNegativeEigenvalues) {
  // A path Laplacian (tightly clustered top for n = 400) shifted so that half the spectrum is
  // negative, plus two eigenvalues 1e-7 apart at the top.
  const int n = 400;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 - 2.0);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  t.emplace_back(n, n, 2.5);
  t.emplace_back(n + 1, n + 1, 2.5 - 1e-7);
  SparseMatrix A(n + 2, n + 2);
  A.setFromTriplets(t.begin(), t.end());
  const Eigen::VectorXd ev = dense_eigenvalues(A);
  const EigenInterval top = certified_largest_eigenvalue(A);
  expect_encloses(top, ev.maxCoeff(), 4.5);
  EXPECT_NEAR(top.hi, 2.5, 1e-9);
  const EigenInterval bottom = certified_smallest_eigenvalue(A);
  expect_encloses(bottom, ev.minCoeff(), 4.5);
  EXPECT_LT(bottom.lo, -1.99);
}

TEST(CertifiedEigenvalue, EntriesBeyondFloatsRangeFallBackToGershgorinsShift) {
  // The estimate runs in float: entries near 1e41 make its tridiagonal infinite, so there is
  // no Ritz value to place a shift (detail/tridiagonal.hpp gives NaN) and the first
  // factorisation is at Gershgorin's bound. The answer is an enclosure, on one thread and on
  // two, but not a narrow one: from that far above a clustered top, inverse iteration does not
  // reach lambda_max, and the certificate just above its Rayleigh quotient fails.
  const SparseMatrix A = plane_matrix(12, 0.2) * 1e40;
  ASSERT_GT(A.coeffs().cwiseAbs().maxCoeff(), 1e41);
  const double top = dense_eigenvalues(A).maxCoeff();
  const GershgorinBounds g = gershgorin_bounds(A);
  for (int threads : {1, 2}) {
    const EigenInterval r = certified_largest_eigenvalue(A, nullptr, threads);
    EXPECT_TRUE(r.certified);
    EXPECT_LE(r.lo, top * (1 + 1e-13));
    EXPECT_GE(r.hi, top);
    EXPECT_LE(r.hi, g.hi + 1e-5 * (g.hi - g.lo));
    EXPECT_GT(r.lo, 0.5 * top);
  }
}

// certified_spectrum analyses the pattern once for both ends (-A has A's pattern): the same
// bits as the two ends computed apart, each with an analysis of its own.
TEST(CertifiedEigenvalue, BothEndsFromOneAnalysisGiveTheBitsOfSeparateCalls) {
  // The 20^3 tetrahedral block's first shift for lambda_max falls below it (Lanczos stalls
  // under the top), so with -A the bottom end, which reuses the top's factorisations, retries
  // its shift as a lone call would.
  const Model block = compile_model(bench::tet_block(20, 20, 20), Params{});
  const SparseMatrix negated_block = -mass_weighted(block, tangent_stiffness(block, block.spec().rest));
  EXPECT_GE(certified_largest_eigenvalue(-negated_block).factorizations, 3);
  for (const SparseMatrix& A : {plane_matrix(14, 0.0), plane_matrix(14, 0.2), negated_block}) {
    const CertifiedSpectrum both = certified_spectrum(A);
    const EigenInterval top = certified_largest_eigenvalue(A);
    const EigenInterval bottom = certified_smallest_eigenvalue(A);
    EXPECT_GT(both.smallest.factorizations, 0);  // no floor given: the bottom factors too
    EXPECT_EQ(both.largest.lo, top.lo);
    EXPECT_EQ(both.largest.hi, top.hi);
    EXPECT_EQ(both.largest.factorizations, top.factorizations);
    EXPECT_EQ(both.smallest.lo, bottom.lo);
    EXPECT_EQ(both.smallest.hi, bottom.hi);
    EXPECT_EQ(both.smallest.factorizations, bottom.factorizations);
    EXPECT_EQ(both.smallest.solves, bottom.solves);
  }
}

TEST(CertifiedEigenvalue, PaperPlaneLambdaMax) {
  // The paper plane (SPEC 5) at kappa = m: lambda_max = 7.8123249218733 (docs/criteria.md).
  const SceneSpec s = paper_plane_scene();
  const Model m = compile_model(s.model, s.params);
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, m.spec().rest));
  const EigenInterval r = certified_largest_eigenvalue(A);
  EXPECT_LE(r.lo, 7.8123249218733 + 1e-12);
  EXPECT_GE(r.hi, 7.8123249218733 - 1e-12);
  EXPECT_LT(r.hi - r.lo, 1e-9);
  // The Lanczos estimate places the first shift above lambda_max: no factorisation fails, and
  // the shift is close enough for a handful of solves (it took 55 with the residual alone).
  EXPECT_GT(r.lanczos_steps, 0);
  EXPECT_EQ(r.factorizations, 2);
  EXPECT_LE(r.solves, 15);
  // The short inverse Lanczos reaches its tolerance before Spectra's 8 + 1 solves.
  EXPECT_LT(r.solves, 8);
}

TEST(CertifiedEigenvalue, ATopClusterTheShortLanczosCannotSplitGoesOnToSpectra) {
  // Twenty eigenvalues 5e-9 apart at the top of a spread of 2.5: the first shift (within about
  // 1e-6 of the top) cannot pull them apart in 8 solves, so the short inverse Lanczos hands
  // over to Spectra's restarted one; the interval must hold all the same.
  const int n = 600;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i)
    t.emplace_back(i, i, i < n - 20 ? 2.0 * i / n : 2.5 - 5e-9 * (n - 1 - i));
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  const EigenInterval top = certified_largest_eigenvalue(A);
  expect_encloses(top, 2.5, 2.5);
  EXPECT_GT(top.solves, 8);
}

TEST(CertifiedEigenvalue, AProvedFloorPinsTheSmallestWithoutFactorising) {
  // A flat plane at rest: its out-of-plane rows hold only the anchors, so lambda_min is the
  // anchor rate kappa_a/m, which psd_floor proves and the smallest diagonal entry attains.
  const Model m = plane_model(12);
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, m.spec().rest));
  ASSERT_GT(A.rows(), 400);  // past the dense path
  const std::optional<double> floor = psd_floor(m, m.spec().rest);
  ASSERT_TRUE(floor.has_value());
  const Eigen::VectorXd ev = dense_eigenvalues(A);
  const GershgorinBounds g = gershgorin_bounds(A);
  const EigenInterval r = certified_smallest_eigenvalue(A, floor);
  expect_encloses(r, ev.minCoeff(), g.hi - g.lo);
  EXPECT_EQ(r.factorizations, 0);
  EXPECT_EQ(certified_spectrum(A, floor).smallest.factorizations, 0);
  // Without the floor the same interval comes from factorisations.
  const EigenInterval without = certified_smallest_eigenvalue(A);
  expect_encloses(without, ev.minCoeff(), g.hi - g.lo);
  EXPECT_GT(without.factorizations, 0);
}

TEST(CertifiedEigenvalue, AFloorFarBelowFallsBackToFactorising) {
  // A floor that is true but not tight (half a unit below lambda_min) proves nothing useful:
  // the factorisations give the interval as before.
  const SparseMatrix A = plane_matrix(12, 0.0);
  const Eigen::VectorXd ev = dense_eigenvalues(A);
  const GershgorinBounds g = gershgorin_bounds(A);
  const EigenInterval r = certified_smallest_eigenvalue(A, ev.minCoeff() - 0.5);
  expect_encloses(r, ev.minCoeff(), g.hi - g.lo);
  EXPECT_GT(r.factorizations, 0);
}

TEST(CertifiedEigenvalue, ABudgetStopsBeforeFactorising) {
  const SparseMatrix A = plane_matrix(12, 0.2);  // 432 rows: the factorisation route
  const EigenInterval free = certified_largest_eigenvalue(A);
  double predicted = 0;
  try {
    certified_largest_eigenvalue(A, nullptr, 1, 1.0);
    ADD_FAILURE() << "a budget of 1 flop did not stop the analysis";
  } catch (const FactorisationOverBudget& over) {
    predicted = over.flops;
    EXPECT_GT(over.flops, 1.0);
    EXPECT_GT(over.bytes, 8.0 * static_cast<double>(A.rows()));  // L holds the diagonal at least
    EXPECT_EQ(over.budget, 1.0);
    EXPECT_NE(std::string(over.what()).find("over the budget of"), std::string::npos) << over.what();
  }
  // Exactly the predicted cost is within budget, and the answer is the same bits.
  const EigenInterval within = certified_largest_eigenvalue(A, nullptr, 1, predicted);
  EXPECT_EQ(within.lo, free.lo);
  EXPECT_EQ(within.hi, free.hi);
  // The smallest end and both ends pass the budget on.
  EXPECT_THROW(certified_smallest_eigenvalue(A, std::nullopt, 1, 1.0), FactorisationOverBudget);
  EXPECT_THROW(certified_spectrum(A, std::nullopt, 1, 1.0), FactorisationOverBudget);
  // Up to 400 rows nothing is factorised, so no budget applies.
  const SparseMatrix small = plane_matrix(11, 0.0);  // 363 rows
  EXPECT_NO_THROW(certified_largest_eigenvalue(small, nullptr, 1, 1.0));
}

/// On two or more threads one of them prepares the factorisations (the matrix and its pattern
/// analysis) while the others run the Lanczos estimate, the first factorisation's rounding
/// bound is taken beside the solves, and the bottom end's estimate runs beside the top end's
/// factorisations: the same bits as on one thread, for both ends of a deformed plane and of a
/// tetrahedral block, and the same answer over a budget.
TEST(CertifiedEigenvalue, WorkBesideTheEstimateGivesTheBitsOfOneThread) {
  const Params p;
  const Model block = compile_model(bench::tet_block(9, 9, 9), p);
  std::vector<Vec3> x = block.spec().rest;
  test::shake(x, 0.01, 17);
  for (const SparseMatrix& A :
       {plane_matrix(30, 0.2), mass_weighted(block, tangent_stiffness(block, x))}) {
    const CertifiedSpectrum one = certified_spectrum(A, std::nullopt, 1);
    EXPECT_GE(one.largest.factorizations, 2);
    EXPECT_GE(one.smallest.factorizations, 2);
    for (int threads : {2, 3}) {
      SCOPED_TRACE(testing::Message() << A.rows() << " rows, " << threads << " threads");
      const CertifiedSpectrum many = certified_spectrum(A, std::nullopt, threads);
      for (auto [a, b] :
           {std::pair{one.largest, many.largest}, std::pair{one.smallest, many.smallest}}) {
        EXPECT_EQ(std::memcmp(&a.lo, &b.lo, sizeof(double)), 0) << a.lo << " vs " << b.lo;
        EXPECT_EQ(std::memcmp(&a.hi, &b.hi, sizeof(double)), 0) << a.hi << " vs " << b.hi;
        EXPECT_EQ(a.lanczos_steps, b.lanczos_steps);
        EXPECT_EQ(a.factorizations, b.factorizations);
        EXPECT_EQ(a.solves, b.solves);
      }
      double flops_one = 0, flops_many = 0;
      try {
        certified_largest_eigenvalue(A, nullptr, 1, 1.0);
      } catch (const FactorisationOverBudget& over) {
        flops_one = over.flops;
      }
      try {
        certified_largest_eigenvalue(A, nullptr, threads, 1.0);
      } catch (const FactorisationOverBudget& over) {
        flops_many = over.flops;
      }
      EXPECT_GT(flops_one, 1.0);
      EXPECT_EQ(flops_many, flops_one);
      EXPECT_THROW(certified_spectrum(A, std::nullopt, threads, 1.0), FactorisationOverBudget);
    }
  }
}

TEST(UnfactoredEigenvalue, BracketsTheTopWithoutFactorising) {
  for (double deform : {0.0, 0.2}) {
    const SparseMatrix A = plane_matrix(16, deform);  // 768 rows
    const double top = dense_eigenvalues(A).maxCoeff();
    Eigen::VectorXd u;
    const EigenInterval r = unfactored_largest_eigenvalue(A, &u, 1, 40);
    EXPECT_EQ(r.factorizations, 0);
    EXPECT_EQ(r.solves, 0);
    EXPECT_LE(r.lanczos_steps, 40);
    EXPECT_LE(r.lo, top);
    EXPECT_GE(r.hi, top);
    EXPECT_EQ(r.hi, gershgorin_bounds(A).hi);
    // The Ritz vector, formed by replaying the recurrence, is near the top: its Rayleigh
    // quotient (less rounding) within 1e-4 of lambda_max.
    EXPECT_GT(r.lo, top - 1e-4 * top) << "deform " << deform;
    EXPECT_NEAR(u.norm(), 1.0, 1e-12);
    EXPECT_NEAR(u.dot(A * u), r.lo, 1e-12 * top);
    // The same bits on two threads.
    Eigen::VectorXd u2;
    const EigenInterval r2 = unfactored_largest_eigenvalue(A, &u2, 2, 40);
    EXPECT_EQ(r2.lo, r.lo);
    EXPECT_EQ(u2, u);
  }
  // No steps: no claim.
  const SparseMatrix A = plane_matrix(12, 0.0);
  const EigenInterval none = unfactored_largest_eigenvalue(A, nullptr, 1, 0);
  EXPECT_TRUE(std::isinf(none.lo) && none.lo < 0);
  EXPECT_TRUE(std::isinf(none.hi) && none.hi > 0);
}

TEST(UnfactoredEigenvalue, AVectorAimedAtAnotherMatrixBoundsBoth) {
  // S = h^2 A + diag(d), d uneven (SPEC 7's index with unequal damping rates): the vector is
  // S's top Ritz vector, and its quotients on A and on S are both lower bounds.
  const SparseMatrix A = plane_matrix(16, 0.2);
  const double h = 0.3;
  Eigen::VectorXd d(A.rows());
  for (Eigen::Index i = 0; i < d.size(); ++i) d(i) = 0.5 + 2.0 * static_cast<double>(i % 17) / 16;
  SparseMatrix S = (h * h) * A;
  for (Eigen::Index i = 0; i < S.rows(); ++i) S.coeffRef(i, i) += d(i);
  const double top_a = dense_eigenvalues(A).maxCoeff(), top_s = dense_eigenvalues(S).maxCoeff();
  Eigen::VectorXd u;
  const EigenInterval r = unfactored_largest_eigenvalue(A, &u, 1, 40, h * h, &d);
  EXPECT_LE(r.lo, top_a);
  EXPECT_GE(r.hi, top_a);
  const double on_s = u.dot(S * u);
  EXPECT_LE(on_s, top_s + 1e-13 * top_s);
  EXPECT_GT(on_s, top_s - 1e-4 * top_s);
  // Aimed at S, the vector says less about A's own top than one aimed at A.
  const EigenInterval own = unfactored_largest_eigenvalue(A, nullptr, 1, 40);
  EXPECT_GE(own.lo, r.lo);
}

TEST(CertifiedEigenvalue, AboveHalfAMillionRowsAmdChecksTheBudgetFirst) {
  // A chain of 600 000 rows (tridiagonal: no fill in any ordering, so the analysis is quick).
  const Eigen::Index n = 600000;
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + 1e-3 * static_cast<double>(i % 7));
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  double predicted = 0;
  try {  // far over: AMD's prediction stops it, and says so
    certified_largest_eigenvalue(A, nullptr, 1, 1.0);
    ADD_FAILURE() << "a budget of 1 flop did not stop the analysis";
  } catch (const FactorisationOverBudget& over) {
    EXPECT_TRUE(over.amd_only);
    EXPECT_NE(std::string(over.what()).find("in AMD's ordering"), std::string::npos) << over.what();
    predicted = over.flops;
    // 600 000 rows in threes: AMD orders the path of 200 000 nodes from its ends, with no
    // fill, so every node column holds 2 nodes but the last (1): row columns of 6, 5, 4
    // entries, and 3, 2, 1 for the last node.
    EXPECT_EQ(over.flops, 199999.0 * (36 + 25 + 16) + (9 + 4 + 1));
    EXPECT_EQ(over.bytes, 8 * (199999.0 * (6 + 5 + 4) + (3 + 2 + 1)));
  }
  try {  // within 32 times: CHOLMOD's own choice of ordering decides (of the rows: 2 per
         // column, 2.4 million flops, a sixth of the estimate by nodes)
    certified_largest_eigenvalue(A, nullptr, 1, predicted / 16);
    ADD_FAILURE() << "half the predicted cost was accepted";
  } catch (const FactorisationOverBudget& over) {
    EXPECT_FALSE(over.amd_only);
    EXPECT_EQ(std::string(over.what()).find("AMD"), std::string::npos) << over.what();
  }
}

/// Calls certified_largest_eigenvalue(A) from two threads at once, `rounds` times, and
/// expects every interval and Ritz vector to be the bits of a lone call's.
void expect_two_at_once_give_the_bits_of_one(const SparseMatrix& A, int rounds) {
  Eigen::VectorXd alone;
  const EigenInterval one = certified_largest_eigenvalue(A, &alone);
  for (int round = 0; round < rounds; ++round) {
    EigenInterval r[2];
    Eigen::VectorXd v[2];
    std::thread other([&] { r[1] = certified_largest_eigenvalue(A, &v[1]); });
    r[0] = certified_largest_eigenvalue(A, &v[0]);
    other.join();
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(r[k].lo, one.lo) << "round " << round << ", thread " << k;
      EXPECT_EQ(r[k].hi, one.hi) << "round " << round << ", thread " << k;
      EXPECT_TRUE(v[k] == alone) << "round " << round << ", thread " << k;
    }
  }
}

SparseMatrix block_matrix(int n) {
  const Model m = compile_model(bench::tet_block(n, n, n), Params{});
  return mass_weighted(m, tangent_stiffness(m, m.spec().rest));
}

TEST(CertifiedEigenvalue, CallsFromTwoThreadsAtOnceGiveTheBitsOfOne) {
  // The tuner's analysis and Suggest workers, or a user's threads, may factorise at the same
  // time. Debian's serial OpenBLAS shares its buffers between threads without a lock: without
  // the turn in CHOLMOD (detail/shifted_cholesky.cpp), 6 to 9 of 12 calls on this block made
  // two at a time differed from the lone call; on the 20^3 block two of ten had a certified
  // hi below lambda_max.
  const SparseMatrix A = block_matrix(14);
  ASSERT_GT(A.rows(), 5000);  // factorised, with separators big enough for OpenBLAS's buffers
  ASSERT_LT(A.rows(), 20000);  // AMD's ordering alone (below kNestedDissectionRows)
  expect_two_at_once_give_the_bits_of_one(A, 3);
}

TEST(CertifiedEigenvalue, AnalysesFromTwoThreadsAtOnceOrderTheMatrixAlike) {
  // Above 20 000 rows CHOLMOD's analysis also tries METIS, which draws from one random
  // generator for the process: with only the factorisations and solves taking turns, every
  // call made two at a time on this block returned a different Ritz vector.
  const SparseMatrix A = block_matrix(20);
  ASSERT_GT(A.rows(), 20000);
  expect_two_at_once_give_the_bits_of_one(A, 1);
}

}  // namespace
}  // namespace dampbound
