// The summary of a sweep: outcome counts and prediction checks on small hand-made grids.
#include "core/sweep/summary.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

SweepRow row(double zeta, Outcome o, int iterations = 10) {
  SweepRow r;
  r.m = 0.001;
  r.kappa = 0.001;
  r.zeta = zeta;
  r.gamma = zeta * 2 * 0.001;
  r.dt = 0.05;
  r.factor = 1;
  r.outcome = o;
  r.iterations = iterations;
  if (o == Outcome::restored) r.first_entry = iterations;
  return r;
}

TEST(SweepSummary, CountsAndPaperChecksOnAHandGrid) {
  const double no_lambda = std::numeric_limits<double>::quiet_NaN();
  const std::vector<SweepRow> rows = {row(0.5, Outcome::not_restored), row(0.5, Outcome::restored),
                                      row(1, Outcome::restored), row(2, Outcome::restored),
                                      row(2, Outcome::diverged)};
  const auto lines = summary_lines(rows, DampingPolicy::fixed, no_lambda);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "outcomes     3 restored, 1 not restored, 1 diverged (of 5 trials)");
  EXPECT_NE(lines[1].find("zeta < 1"), std::string::npos);
  EXPECT_NE(lines[1].find("held in 1 of 2 (50.0%)"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find("held in 2 of 3 (66.7%)"), std::string::npos) << lines[2];
  EXPECT_EQ(rows_rule(rows), StopRule::first_entry);
}

TEST(SweepSummary, PoliciesPickTheirChecks) {
  const double no_lambda = std::numeric_limits<double>::quiet_NaN();
  std::vector<SweepRow> rows = {row(1, Outcome::restored), row(1, Outcome::diverged)};
  rows[1].factor = 1.5;
  const auto upper = check_predictions(rows, DampingPolicy::upper, no_lambda);
  ASSERT_EQ(upper.size(), 2u);
  EXPECT_EQ(upper[0].held, 1u);
  EXPECT_EQ(upper[0].of, 1u);
  EXPECT_EQ(upper[1].held, 1u);
  EXPECT_EQ(upper[1].of, 1u);
  const auto clamp = check_predictions(rows, DampingPolicy::clamp, no_lambda);
  ASSERT_EQ(clamp.size(), 1u);
  EXPECT_EQ(clamp[0].held, 1u);
  EXPECT_EQ(clamp[0].of, 2u);
  EXPECT_TRUE(check_predictions(rows, DampingPolicy::safe, no_lambda).empty());
  EXPECT_TRUE(check_predictions(rows, std::nullopt, 3.0).empty());
  // With lambda the fixed policy adds the exact linear checks (SPEC 7).
  // Both rows are linearly stable: only the "stable => not diverged" check applies.
  const auto fixed = check_predictions(rows, DampingPolicy::fixed, 3.0);
  ASSERT_EQ(fixed.size(), check_predictions(rows, DampingPolicy::fixed, no_lambda).size() + 1);
  EXPECT_EQ(fixed.back().claim, "linearly stable => not diverged");
  EXPECT_EQ(fixed.back().held, 1u);
  EXPECT_EQ(fixed.back().of, 2u);
}

TEST(SweepSummary, SettledRuleCountsOverturnedVerdicts) {
  std::vector<SweepRow> rows = {row(1, Outcome::settled), row(1, Outcome::not_settled),
                                row(1, Outcome::diverged), row(0.5, Outcome::not_settled)};
  rows[0].first_entry = 5;
  rows[1].first_entry = 7;
  rows[2].first_entry = 9;
  EXPECT_EQ(rows_rule(rows), StopRule::settled);
  const Overturned o = count_overturned(rows);
  EXPECT_EQ(o.entered, 3u);
  EXPECT_EQ(o.left, 1u);
  EXPECT_EQ(o.diverged, 1u);
  const auto lines = summary_lines(rows, DampingPolicy::fixed, std::nan(""));
  ASSERT_GE(lines.size(), 2u);
  EXPECT_EQ(lines[0],
            "outcomes     1 settled, 2 not settled (1 of them entered the band, then left), 1 "
            "diverged (of 4 trials; settled rule)");
  EXPECT_NE(lines[1].find("2 of 3 first-entry restores (66.67%)"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find("[settled rule]"), std::string::npos);
}

TEST(SweepSummary, LinearLimitOfSpec7) {
  // lambda = 4 (unit 1, kappa/m = 4), m = 1, dt = 0.5: gamma_max = 2/0.5 - 4*0.5/2 = 3.
  EXPECT_FALSE(linearly_unstable(1, 4, 2.9, 0.5, 1));
  EXPECT_TRUE(linearly_unstable(1, 4, 3.0, 0.5, 1));
  EXPECT_TRUE(linearly_unstable(1, 4, 4.0, 0.5, 1));  // gamma dt/m = 2
  EXPECT_FALSE(linearly_unstable(1, 4, 0, 0.5, 1));   // marginal, not unstable
  EXPECT_TRUE(linearly_unstable(1, 4, 0, 1.0, 1));    // dt beyond 2/sqrt(lambda)
}

TEST(SweepSummary, DefinitionValues) {
  const std::string d = "m=1 kappa=2 policy=fixed max-iter=300 xpolicy=no";
  EXPECT_EQ(definition_value(d, "policy"), "fixed");
  EXPECT_EQ(definition_value(d, "m"), "1");
  EXPECT_EQ(definition_value(d, "max-iter"), "300");
  EXPECT_EQ(definition_value(d, "rule"), std::nullopt);
  EXPECT_EQ(definition_value("xm=1 m=2", "m"), "2");
}

TEST(SweepSummary, UnitEigenvalueScalesWithTheScene) {
  const SceneSpec scene = test::shipped_scene("two-node");
  const double l = unit_stiffness_eigenvalue(scene);
  EXPECT_TRUE(std::isfinite(l));
  EXPECT_GT(l, 0);
}

}  // namespace
}  // namespace dampbound
