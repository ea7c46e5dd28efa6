// Newton from the right (core/analysis/detail/newton.hpp): the root of a convex increasing
// function to rounding, from the right whichever side it starts, and one evaluation fewer than
// stepping until a step falls below 1e-13 of the iterate.
#include "core/analysis/detail/newton.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

namespace dampbound::detail {
namespace {

/// g(t) = t^2 - 2 and its slope, counting the evaluations.
struct Square {
  int calls = 0;
  std::pair<double, double> operator()(double t) {
    ++calls;
    return {t * t - 2, 2 * t};
  }
};

/// The evaluations a rule that stops only on a step below 1e-13 t makes, from t.
int plain_newton_calls(double t) {
  for (int calls = 1;; ++calls) {
    const double next = t - (t * t - 2) / (2 * t);
    if (std::abs(next - t) <= 1e-13 * t) return calls;
    t = next;
  }
}

TEST(NewtonFromRight, TheRootToRoundingWithOneEvaluationFewer) {
  const double root = std::sqrt(2.0);
  for (const double start : {10.0, 2.0, 1.5}) {
    Square g;
    const double r = newton_from_right(std::ref(g), start);
    EXPECT_NEAR(r, root, 4e-16) << start;
    EXPECT_GE(r * r - 2, -4e-16) << start;  // on the side where g >= 0, within rounding
    EXPECT_EQ(g.calls, plain_newton_calls(start) - 1) << start;
  }
}

TEST(NewtonFromRight, AnEarlierSlopeLetsTheFirstStepStop) {
  // From 1e-8 right of the root the first step leaves an error of about 3.5e-17: with the
  // slope of an earlier evaluation (at 1.5) the curvature is known and that step is the last.
  const double root = std::sqrt(2.0), start = root + 1e-8;
  Square with, without;
  const double a = newton_from_right(std::ref(with), start, std::make_pair(1.5, 3.0));
  const double b = newton_from_right(std::ref(without), start);
  EXPECT_EQ(with.calls, 1);
  EXPECT_EQ(without.calls, 2);
  EXPECT_NEAR(a, root, 4e-16);
  EXPECT_NEAR(b, root, 4e-16);
  // The step from the scene's own point, computed by the caller, lands right of the root.
  EXPECT_GT(newton_step(1.0, -1.0, 2.0), root);
  EXPECT_TRUE(std::isnan(newton_step(1.0, -1.0, 0.0)));
}

TEST(NewtonFromRight, FromTheLeftTheFirstStepLandsRight) {
  Square g;
  const double r = newton_from_right(std::ref(g), 1.0);  // g(1) = -1
  EXPECT_NEAR(r, std::sqrt(2.0), 4e-16);
}

TEST(NewtonFromRight, AKinkDoesNotStopItEarly) {
  // Convex and piecewise linear: slope 1 below t = 1, 100 above, root at 0.5. From the right
  // the first step lands on the kink's far side; the slopes' difference there says nothing of
  // the next step, and the rule must not take it as convergence.
  int calls = 0;
  const auto g = [&calls](double t) {
    ++calls;
    return t < 1 ? std::make_pair(t - 0.5, 1.0) : std::make_pair(0.5 + 100 * (t - 1), 100.0);
  };
  EXPECT_DOUBLE_EQ(newton_from_right(g, 3.0), 0.5);
}

TEST(NewtonFromRight, ZeroWhereTheFunctionIsPositiveDownToZero) {
  const auto g = [](double t) { return std::make_pair(t + 1, 1.0); };  // root at -1
  EXPECT_EQ(newton_from_right(g, 2.0), 0.0);
}

}  // namespace
}  // namespace dampbound::detail
