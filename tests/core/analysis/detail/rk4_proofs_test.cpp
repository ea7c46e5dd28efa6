// Tests of core/analysis/detail/rk4_proofs: RK4's per-mode certificates against the step's
// eigenvalues R(h mu) computed directly (mu the roots of mu^2 + c mu + lambda), on grids of
// modes, steps and rates; and against RK4's known ends (the imaginary axis to 2 sqrt 2, the
// real axis to -2.7852936).
#include "core/analysis/detail/rk4_proofs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

namespace dampbound::detail {
namespace {

constexpr double kE1 = 1 + 1e-12;

/// The spectral radius of RK4's step for the mode lambda at rate c and step h, directly.
double radius(double lambda, double c, double h) {
  using C = std::complex<long double>;
  const C root = std::sqrt(C(static_cast<long double>(c) * c - 4.0L * lambda, 0));
  double r = 0;
  for (const C mu : {(-C(c, 0) + root) / 2.0L, (-C(c, 0) - root) / 2.0L}) {
    const C z = mu * static_cast<long double>(h);
    const C R = 1.0L + z + z * z / 2.0L + z * z * z / 6.0L + z * z * z * z / 24.0L;
    r = std::max(r, static_cast<double>(std::abs(R)));
  }
  return r;
}

/// The largest radius over lambda in [0, lambda_hi] (samples, both ends included).
double worst_radius(double lambda_hi, double c, double h, int samples = 400) {
  double r = 0;
  for (int k = 0; k <= samples; ++k) r = std::max(r, radius(lambda_hi * k / samples, c, h));
  return r;
}

TEST(Rk4Proofs, UndampedInstabilityStartsWhereTheImaginaryAxisLeavesTheRegion) {
  // c = 0: |R(iy)|^2 = 1 - y^6/72 + y^8/576, 1 at y^2 = 8 and above it beyond.
  const double h = 0.1, from = rk4_lambda_from(0, h, kE1);
  EXPECT_GT(from * h * h, 8);
  EXPECT_NEAR(from * h * h, 8, 1e-6);
  for (double f : {1.0, 1.0001, 1.01, 1.5, 3.0, 100.0, 1e4})
    EXPECT_GT(radius(from * f, 0, h), kE1) << f;
  EXPECT_LT(radius(0.999 * from, 0, h), 1);
}

TEST(Rk4Proofs, DampedInstabilityIsCertifiedFromItsThresholdOnAndIsTight) {
  for (const double c : {0.5, 3.0, 12.0}) {
    const double h = 0.1, from = rk4_lambda_from(c, h, kE1);
    ASSERT_TRUE(std::isfinite(from)) << c;
    EXPECT_GE(from, c * c / 4);
    // Every mode from the threshold on is unstable (samples up to 1e6 times it).
    for (int k = 0; k <= 300; ++k) {
      const double lambda = from * std::pow(10.0, 6.0 * k / 300);
      EXPECT_GT(radius(lambda, c, h), kE1) << "c " << c << " lambda " << lambda;
    }
    // Tight: just below it the mode is stable.
    EXPECT_LE(radius(from * (1 - 1e-4), c, h), kE1) << c;
  }
}

TEST(Rk4Proofs, ModesPastTheRealIntervalAreUnstableFromTheDoubleRootOn) {
  // c h = 6: the double root's z = -3 lies beyond -2.7852936, |R(-3)| = 1.375.
  const double c = 60, h = 0.1, from = rk4_lambda_from(c, h, kE1);
  EXPECT_DOUBLE_EQ(from, c * c / 4 * kRoundUp);
  EXPECT_GT(radius(c * c / 4, c, h), kE1);
  for (double f : {1.0, 1.1, 10.0, 1e3}) EXPECT_GT(radius(from * f, c, h), kE1) << f;
}

TEST(Rk4Proofs, EveryStepUpToTheProvedOneIsStableForEveryModeAndItIsNearlyTheLargest) {
  for (const double c : {0.0, 5.0, 40.0}) {
    const double lambda_hi = 100;
    const double S = rk4_dt_up_to(lambda_hi, c, kE1);
    ASSERT_GT(S, 0) << c;
    for (int k = 1; k <= 100; ++k)
      EXPECT_LE(worst_radius(lambda_hi, c, S * k / 100), kE1) << "c " << c << " h " << S * k / 100;
    // The true largest step by bisection on the sampled radius: S is within 1 % of it.
    double lo = S, hi = 2 * S;
    while (worst_radius(lambda_hi, c, hi) <= kE1) hi *= 2;
    for (int k = 0; k < 40; ++k) {
      const double mid = (lo + hi) / 2;
      (worst_radius(lambda_hi, c, mid) <= kE1 ? lo : hi) = mid;
    }
    EXPECT_GE(S, 0.99 * lo) << c;
    if (c == 0) {
      EXPECT_NEAR(S * std::sqrt(lambda_hi), 2 * std::sqrt(2.0), 1e-3);
    }
  }
}

TEST(Rk4Proofs, TheRateRangeHoldsOnlyStableRatesAndContainsAProvedRate) {
  const double h = 0.1;
  const double cap = 2.78529 / h;
  for (const double lambda_hi : {10.0, 500.0, 790.0}) {
    const double c = 2;
    const auto [lo, hi] = rk4_rate_range(lambda_hi, c, h, kE1);
    ASSERT_LE(lo, hi) << lambda_hi;
    EXPECT_LE(lo, c);
    EXPECT_GE(hi, c);
    EXPECT_LE(hi, cap);
    EXPECT_GE(lo, 0);
    for (int k = 0; k <= 100; ++k) {
      const double rate = lo + (hi - lo) * k / 100;
      EXPECT_LE(worst_radius(lambda_hi, rate, h), kE1)
          << "lambda_hi " << lambda_hi << " rate " << rate;
    }
  }
  // Past the real interval's end (rate h = 2.9: z = -2.9 at lambda = 0) is unstable.
  EXPECT_GT(radius(0, 29, h), kE1);
}

TEST(Rk4Proofs, ARateNotProvedGivesTheNearestProvedRangeOrNone) {
  const double h = 0.1;
  // lambda_hi h^2 = 8.3 > 8: no damping leaves the top undamped mode unstable.
  const double lambda_hi = 830, c = 0;
  EXPECT_GT(worst_radius(lambda_hi, c, h), kE1);
  const auto [lo, hi] = rk4_rate_range(lambda_hi, c, h, kE1);
  if (lo <= hi) {
    EXPECT_GT(lo, c);
    for (int k = 0; k <= 50; ++k)
      EXPECT_LE(worst_radius(lambda_hi, lo + (hi - lo) * k / 50, h), kE1);
  }
  // Far past every damped mode's reach: none.
  const auto none = rk4_rate_range(1e5, 1, h, kE1);
  EXPECT_GT(none.first, none.second);
  EXPECT_GT(worst_radius(1e5, 1, h), kE1);
}

}  // namespace
}  // namespace dampbound::detail
