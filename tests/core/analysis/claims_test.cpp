// Claim verdicts follow the measured outcomes.
#include "core/analysis/claims.hpp"
#include "core/io/scene_file.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "tests/core/test_util.hpp"

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

/// A settled-rule result: outcome, first entry, exit and settled iteration.
RunResult judged(Outcome o, int first, int left, int settled_at, int iterations = 1000) {
  RunResult r;
  r.outcome = o;
  r.first_entry = first;
  r.left_at = left;
  r.settled_at = settled_at;
  r.iterations = iterations;
  return r;
}

TEST(Claims, Fig1Verdicts) {
  const RunResult never = judged(Outcome::not_settled, 0, 0, 0);
  auto c = fig1_claims(fake({{Outcome::not_restored, 1000},
                             {Outcome::not_restored, 1000},
                             {Outcome::restored, 34}}),
                       {never, never, judged(Outcome::settled, 34, 0, 34)});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].verdict, ClaimVerdict::holds);
  EXPECT_EQ(c[0].rule, StopRule::settled);
  EXPECT_EQ(c[1].verdict, ClaimVerdict::holds);
  EXPECT_EQ(c[1].rule, StopRule::first_entry);
  EXPECT_NE(c[1].measured.find("both rules"), std::string::npos);
  // A first entry that is left again is no return to rest: the claim is judged as settled.
  c = fig1_claims(fake({{Outcome::restored, 230}, {Outcome::restored, 108},
                        {Outcome::restored, 112}}),
                  {judged(Outcome::not_settled, 230, 240, 0), judged(Outcome::settled, 108, 109, 150),
                   judged(Outcome::settled, 112, 0, 112)});
  EXPECT_EQ(c[0].verdict, ClaimVerdict::partly);
  EXPECT_NE(c[0].measured.find("left it at 240"), std::string::npos);
  EXPECT_EQ(c[1].verdict, ClaimVerdict::partly);
  EXPECT_NE(c[1].measured.find("112"), std::string::npos);
  c = fig1_claims(fake({{Outcome::restored, 230}, {Outcome::restored, 108},
                        {Outcome::diverged, 3}}),
                  {judged(Outcome::settled, 230, 231, 260), judged(Outcome::settled, 108, 0, 108),
                   judged(Outcome::diverged, 0, 0, 0, 3)});
  EXPECT_EQ(c[0].verdict, ClaimVerdict::does_not_hold);
  EXPECT_EQ(c[1].verdict, ClaimVerdict::does_not_hold);
}

TEST(Claims, Fig2Verdicts) {
  const FigureData paper = fake({{Outcome::restored, 110}, {Outcome::restored, 85}});
  auto c = fig2_claims(paper, {judged(Outcome::settled, 110, 0, 110, 10000),
                               judged(Outcome::diverged, 85, 90, 0, 400)});
  EXPECT_EQ(c[0].verdict, ClaimVerdict::holds);
  EXPECT_EQ(c[1].verdict, ClaimVerdict::holds);  // diverged after its first entry
  EXPECT_EQ(c[1].rule, StopRule::settled);
  c = fig2_claims(paper, {judged(Outcome::settled, 110, 111, 700, 10000),
                          judged(Outcome::settled, 85, 0, 85, 10000)});
  EXPECT_EQ(c[0].verdict, ClaimVerdict::partly);  // settled, but after 652
  EXPECT_EQ(c[1].verdict, ClaimVerdict::does_not_hold);
  c = fig2_claims(paper, {judged(Outcome::diverged, 110, 111, 0, 5000),
                          judged(Outcome::not_settled, 85, 86, 0, 10000)});
  EXPECT_EQ(c[0].verdict, ClaimVerdict::partly);  // entered by 652, never settled
  EXPECT_NE(c[0].measured.find("diverged at 5000"), std::string::npos);
  EXPECT_EQ(c[1].verdict, ClaimVerdict::partly);
}

TEST(Claims, SettledResultsRunEachFigureRunToItsLimit) {
  const SceneSpec s = load_scene(test::source_path("scenes/two-node.toml"));
  FigureData fig;
  FigureRun run;
  run.params = s.params;
  run.params.gamma = 0;  // undamped: passes through the band at 31 and out again
  run.rules = s.rules;
  run.rules.max_iterations = 300;
  fig.runs.push_back(run);
  const std::vector<RunResult> r = settled_results(s, fig);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].outcome, Outcome::not_settled);
  EXPECT_EQ(r[0].iterations, 300);
  EXPECT_EQ(r[0].first_entry, 31);
}

TEST(Claims, TableHasEveryClaim) {
  std::vector<Claim> c(2);
  c[0].paper = "A";
  c[1].paper = "B";
  c[1].verdict = ClaimVerdict::holds;
  std::ostringstream os;
  write_claims_table(os, c);
  EXPECT_NE(os.str().find("| 1 |  | A |  | first-entry | **does not hold** |"), std::string::npos);
  EXPECT_NE(os.str().find("| 2 |  | B |  | first-entry | **holds** |"), std::string::npos);
}

}  // namespace
}  // namespace dampbound
