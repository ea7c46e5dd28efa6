// Claim verdicts follow the measured outcomes.
#include "core/claims.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "test_util.hpp"

namespace dampbound {
namespace {

FigureData fake(std::vector<std::pair<Outcome, int>> results) {
  FigureData f;
  for (auto [o, n] : results) {
    FigureRun r;
    r.result.outcome = o;
    r.result.iterations = n;
    f.runs.push_back(r);
  }
  return f;
}

TEST(Claims, Fig1Verdicts) {
  auto c = fig1_claims(fake({{Outcome::not_restored, 1000},
                             {Outcome::not_restored, 1000},
                             {Outcome::restored, 34}}));
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].verdict, ClaimVerdict::holds);
  EXPECT_EQ(c[1].verdict, ClaimVerdict::holds);
  c = fig1_claims(fake({{Outcome::restored, 230}, {Outcome::not_restored, 1000},
                        {Outcome::restored, 112}}));
  EXPECT_EQ(c[0].verdict, ClaimVerdict::partly);
  EXPECT_EQ(c[1].verdict, ClaimVerdict::partly);
  EXPECT_NE(c[1].measured.find("112"), std::string::npos);
  c = fig1_claims(fake({{Outcome::restored, 230}, {Outcome::restored, 108},
                        {Outcome::diverged, 3}}));
  EXPECT_EQ(c[0].verdict, ClaimVerdict::does_not_hold);
  EXPECT_EQ(c[1].verdict, ClaimVerdict::does_not_hold);
}

TEST(Claims, Fig2Verdicts) {
  AfterRestore stays;
  stays.restored = true;
  stays.restored_at = 110;
  stays.until = 10000;
  auto c = fig2_claims(fake({{Outcome::restored, 110}, {Outcome::diverged, 400}}), stays);
  EXPECT_EQ(c[0].verdict, ClaimVerdict::holds);
  EXPECT_EQ(c[1].verdict, ClaimVerdict::holds);
  c = fig2_claims(fake({{Outcome::restored, 700}, {Outcome::restored, 85}}), stays);
  EXPECT_EQ(c[0].verdict, ClaimVerdict::partly);
  EXPECT_EQ(c[1].verdict, ClaimVerdict::does_not_hold);
  AfterRestore blows = stays;
  blows.diverged = true;
  blows.diverged_at = 5000;
  c = fig2_claims(fake({{Outcome::restored, 110}, {Outcome::diverged, 400}}), blows);
  EXPECT_EQ(c[0].verdict, ClaimVerdict::partly);
  EXPECT_NE(c[0].measured.find("diverged at iteration 5000"), std::string::npos);
}

TEST(Claims, AfterRestoreStepsOn) {
  const SceneSpec s = load_scene(test::source_path("scenes/two-node.toml"));
  FigureRun run;
  run.params = s.params;
  run.params.gamma = 0.004;  // overdamped: creeps back, stays
  run.rules = s.rules;
  const AfterRestore a = run_after_restore(s, run, 2000);
  EXPECT_TRUE(a.restored);
  EXPECT_FALSE(a.diverged);
  EXPECT_GT(a.restored_at, 1);
  EXPECT_LT(a.max_after, a.threshold);
}

TEST(Claims, TableHasEveryClaim) {
  std::vector<Claim> c(2);
  c[0].paper = "A";
  c[1].paper = "B";
  c[1].verdict = ClaimVerdict::holds;
  std::ostringstream os;
  write_claims_table(os, c);
  EXPECT_NE(os.str().find("| 1 |  | A |  | **does not hold** |"), std::string::npos);
  EXPECT_NE(os.str().find("| 2 |  | B |  | **holds** |"), std::string::npos);
}

}  // namespace
}  // namespace dampbound
