// Tests of core/analysis/criteria_unfactored: the four exact rows over the factorisation
// budget, from an ExactStability built by hand: each row names its reason, no row has a value
// from a factorisation, and each verdict follows what the unfactored bounds prove (the
// paper's step's index, the per-mode thresholds, RK4's stable side, implicit Euler's
// unconditional stability), with no verdict between the proofs.
#include "core/analysis/criteria_unfactored.hpp"
#include "core/physics/detail/numbers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace dampbound {
namespace {


ExactStability not_computed(Integrator integ) {
  ExactStability e;
  e.integrator = integ;
  e.method = ExactMethod::over_budget;
  e.not_computed_reason = "one factorisation would take 9e9 flops";
  e.unfactored.lambda_max_lo = 90;
  e.unfactored.lambda_max_hi = 110;
  e.unfactored.gershgorin = 120;
  e.unfactored.lanczos_steps = 40;
  return e;
}

Params params(Integrator integ, double gamma, double dt) {
  Params p;
  p.integrator = integ;
  p.gamma = gamma;
  p.dt = dt;
  return p;
}

bool mentions(const CriterionResult& c, const std::string& text) {
  return c.test.find(text) != std::string::npos;
}

TEST(CriteriaUnfactored, NothingTriedGivesFourRowsWithTheReasonAndNoVerdict) {
  ExactStability e = not_computed(Integrator::semi_implicit_euler);
  e.unfactored = {};  // NaN: not tried
  const auto rows = unfactored_criteria(e, params(Integrator::semi_implicit_euler, 0.1, 0.05));
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].name, "exact lambda_max of M^-1 K");
  EXPECT_EQ(rows[3].name,
            std::string("exact dt limit (") + to_string(Integrator::semi_implicit_euler) + ")");
  for (const auto& c : rows) {
    EXPECT_EQ(c.verdict, CriterionVerdict::not_applicable) << c.name;
    EXPECT_TRUE(std::isnan(c.value)) << c.name;
    EXPECT_EQ(c.test, "not computed: one factorisation would take 9e9 flops") << c.name;
  }
}

TEST(CriteriaUnfactored, TheLambdaRowGivesTheBracketAndWhichBoundClosesIt) {
  const ExactStability e = not_computed(Integrator::semi_implicit_euler);
  const auto rows = unfactored_criteria(e, params(Integrator::semi_implicit_euler, 0.1, 0.05));
  EXPECT_TRUE(mentions(rows[0], "Lanczos, 40 steps")) << rows[0].test;
  EXPECT_TRUE(mentions(rows[0], "lambda_max in [90, 110]")) << rows[0].test;
  EXPECT_TRUE(mentions(rows[0], "the node-block splitting's bound; Gershgorin's: 120")) << rows[0].test;
  EXPECT_TRUE(std::isnan(rows[0].value));
}

TEST(CriteriaUnfactored, ThePaperStepsIndexProvesInstabilityAtFourAndItsThresholds) {
  ExactStability e = not_computed(Integrator::semi_implicit_euler);
  auto& b = e.unfactored;
  b.index_at_least = 4.5;
  b.gamma_unstable_from = 0.08;
  b.dt_unstable_from = 0.04;
  const auto rows = unfactored_criteria(e, params(Integrator::semi_implicit_euler, 0.1, 0.05));
  EXPECT_EQ(rows[1].verdict, CriterionVerdict::beyond);
  EXPECT_TRUE(mentions(rows[1], ">= 4: unstable (proved)")) << rows[1].test;
  EXPECT_EQ(rows[2].verdict, CriterionVerdict::beyond);
  EXPECT_TRUE(mentions(rows[2], "every gamma >= 0.08 is unstable at this dt")) << rows[2].test;
  EXPECT_EQ(rows[3].verdict, CriterionVerdict::beyond);
  EXPECT_TRUE(mentions(rows[3], "every dt >= 0.04 is unstable at this gamma")) << rows[3].test;
  // Below both thresholds and with nothing proved stable: no verdict.
  b.index_at_least = 3;
  const auto open = unfactored_criteria(e, params(Integrator::semi_implicit_euler, 0.05, 0.03));
  for (size_t k = 1; k < 4; ++k)
    EXPECT_EQ(open[k].verdict, CriterionVerdict::not_applicable) << open[k].test;
  EXPECT_TRUE(mentions(open[1], "(< 4 proves nothing)")) << open[1].test;
  EXPECT_TRUE(mentions(open[2], "gamma = 0.05 is not proved either way")) << open[2].test;
  // The user's point exactly at a threshold counts as unstable.
  const auto at = unfactored_criteria(e, params(Integrator::semi_implicit_euler, 0.08, 0.04));
  EXPECT_EQ(at[2].verdict, CriterionVerdict::beyond);
  EXPECT_EQ(at[3].verdict, CriterionVerdict::beyond);
}

TEST(CriteriaUnfactored, ThePaperStepsUpperBoundBelowFourProvesStability) {
  ExactStability e = not_computed(Integrator::semi_implicit_euler);
  auto& b = e.unfactored;
  b.index_at_least = 1;
  b.index_at_most = 2;
  b.index_gershgorin = 2;
  b.gamma_unstable_from = 0.5;
  b.dt_unstable_from = 0.2;
  b.gamma_stable_lo = 0;
  b.gamma_stable_hi = 0.3;
  b.dt_stable_up_to = 0.1;
  e.stable = true;
  const auto rows = unfactored_criteria(e, params(Integrator::semi_implicit_euler, 0.1, 0.05));
  for (size_t k = 1; k < 4; ++k) EXPECT_EQ(rows[k].verdict, CriterionVerdict::within) << k;
  EXPECT_TRUE(mentions(rows[1], "< 4: stable (proved)")) << rows[1].test;
  EXPECT_TRUE(mentions(rows[2], "every gamma <= 0.3 is stable; gamma = 0.1 is stable")) << rows[2].test;
  EXPECT_TRUE(mentions(rows[3], "every dt <= 0.1 is stable; dt = 0.05 is stable")) << rows[3].test;
  // Outside the stable ranges but below the unstable thresholds: no verdict.
  const auto between = unfactored_criteria(e, params(Integrator::semi_implicit_euler, 0.4, 0.15));
  EXPECT_EQ(between[2].verdict, CriterionVerdict::not_applicable) << between[2].test;
  EXPECT_EQ(between[3].verdict, CriterionVerdict::not_applicable) << between[3].test;
}

TEST(CriteriaUnfactored, PerModeThresholdsProveInstabilityBelowAGammaAndAboveADt) {
  ExactStability e = not_computed(Integrator::forward_euler);
  auto& b = e.unfactored;
  b.mode_unstable_from = 80;  // lambda_max_lo = 90 reaches it
  b.gamma_unstable_below = 0.3;
  b.dt_unstable_from = 0.04;
  const auto rows = unfactored_criteria(e, params(Integrator::forward_euler, 0.2, 0.05));
  EXPECT_EQ(rows[1].verdict, CriterionVerdict::beyond);
  EXPECT_TRUE(mentions(rows[1], "every mode with lambda >= 80")) << rows[1].test;
  EXPECT_EQ(rows[2].verdict, CriterionVerdict::beyond);
  EXPECT_TRUE(mentions(rows[2], "every gamma <= 0.3 is unstable at this dt")) << rows[2].test;
  EXPECT_EQ(rows[3].verdict, CriterionVerdict::beyond);
  // A gamma above the threshold is not proved unstable.
  b.mode_unstable_from = 100;
  const auto above = unfactored_criteria(e, params(Integrator::forward_euler, 0.35, 0.03));
  EXPECT_EQ(above[1].verdict, CriterionVerdict::not_applicable) << above[1].test;
  EXPECT_EQ(above[2].verdict, CriterionVerdict::not_applicable) << above[2].test;
  EXPECT_EQ(above[3].verdict, CriterionVerdict::not_applicable) << above[3].test;
  // No damping anywhere: every gamma is unstable.
  b.gamma_unstable_below = kInf;
  const auto undamped = unfactored_criteria(e, params(Integrator::forward_euler, 0.35, 0.03));
  EXPECT_EQ(undamped[2].verdict, CriterionVerdict::beyond);
  EXPECT_TRUE(mentions(undamped[2], "every gamma is unstable at this dt")) << undamped[2].test;
}

TEST(CriteriaUnfactored, Rk4GivesItsStableSideAroundTheUsersPointAndNoThresholds) {
  ExactStability e = not_computed(Integrator::rk4);
  auto& b = e.unfactored;
  b.mode_unstable_from = 200;
  b.dt_unstable_from = kNaN;
  b.gamma_unstable_below = kNaN;
  b.stable_lambda_hi = 110;
  b.gamma_stable_lo = 0.05;
  b.gamma_stable_hi = 0.5;
  b.dt_stable_up_to = 0.08;
  e.stable = true;
  const auto rows = unfactored_criteria(e, params(Integrator::rk4, 0.1, 0.05));
  for (size_t k = 1; k < 4; ++k) EXPECT_EQ(rows[k].verdict, CriterionVerdict::within) << k;
  EXPECT_TRUE(mentions(rows[2], "every gamma in [0.05, 0.5] is stable")) << rows[2].test;
  EXPECT_TRUE(mentions(rows[3], "every dt <= 0.08 is stable")) << rows[3].test;
  EXPECT_FALSE(mentions(rows[2], "unstable")) << rows[2].test;
  // Proved unstable at the user's point: the two limit rows follow the radius row.
  b.mode_unstable_from = 85;
  e.stable = false;
  const auto beyond = unfactored_criteria(e, params(Integrator::rk4, 0.1, 0.05));
  for (size_t k = 1; k < 4; ++k) EXPECT_EQ(beyond[k].verdict, CriterionVerdict::beyond) << k;
  EXPECT_TRUE(mentions(beyond[3], "unstable at this gamma and dt (proved")) << beyond[3].test;
}

TEST(CriteriaUnfactored, ImplicitEulerWithKPositiveSemidefiniteIsStableForEveryDtAndGamma) {
  ExactStability e = not_computed(Integrator::implicit_euler);
  e.unfactored.unconditional = true;
  e.stable = true;
  const auto rows = unfactored_criteria(e, params(Integrator::implicit_euler, 0.1, 10));
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].verdict, CriterionVerdict::not_applicable);
  for (size_t k = 1; k < 4; ++k) EXPECT_EQ(rows[k].verdict, CriterionVerdict::within) << k;
  EXPECT_EQ(rows[2].value, kInf);
  EXPECT_EQ(rows[3].value, kInf);
  EXPECT_TRUE(mentions(rows[3], "dt = 10 <= dt_max = inf")) << rows[3].test;
}

}  // namespace
}  // namespace dampbound
