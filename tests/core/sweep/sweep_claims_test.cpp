// A sweep's prediction checks become the paper's claims, judged under both rules.
#include "core/sweep/sweep_claims.hpp"

#include <gtest/gtest.h>

namespace dampbound {
namespace {

TEST(SweepClaims, OnlyThePapersChecksWithTrialsBecomeClaims) {
  std::vector<PredictionCheck> checks(4);
  checks[0].claim = "gamma >= lower bound => restored within the limit (paper Fig. 1)";
  checks[0].held = 625;
  checks[0].of = 625;
  checks[1].claim = "gamma < lower bound => not settled (paper sec. 4) [settled rule]";
  checks[1].held = 40;
  checks[1].of = 1250;
  checks[2].claim = "exact limit agrees with the run";  // dampbound's own: not a claim
  checks[2].held = 3;
  checks[2].of = 3;
  checks[3].claim = "gamma > upper bound => diverged (paper sec. 4)";  // no trials: none
  const std::vector<Claim> c = sweep_claims(checks, "sec. 4", "50 x 50");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].verdict, ClaimVerdict::holds);
  EXPECT_EQ(c[0].rule, StopRule::first_entry);
  EXPECT_EQ(c[0].measured, "held in 625 of 625 trials (100.0%) on 50 x 50");
  EXPECT_EQ(c[1].verdict, ClaimVerdict::partly);
  EXPECT_EQ(c[1].rule, StopRule::settled);
  EXPECT_EQ(c[1].source, "sec. 4");
  checks[1].held = 0;
  EXPECT_EQ(sweep_claims(checks, "sec. 4", "g").at(1).verdict, ClaimVerdict::does_not_hold);
}

TEST(SweepClaims, BothRulesPairedByPosition) {
  std::vector<Claim> f(2), st(2);
  f[0].paper = "gamma < lower bound => not restored (paper sec. 4)";
  f[0].measured = "held in 7 of 1250 trials";
  f[0].verdict = ClaimVerdict::partly;
  f[1].paper = "gamma >= lower bound => restored within the limit (paper Fig. 1)";
  f[1].measured = "held in 625 of 625 trials";
  f[1].verdict = ClaimVerdict::holds;
  st[0].paper = "gamma < lower bound => not settled (paper sec. 4) [settled rule]";
  st[0].measured = "held in 40 of 1250 trials";
  st[0].rule = StopRule::settled;
  st[0].verdict = ClaimVerdict::partly;
  st[1] = f[1];
  st[1].rule = StopRule::settled;
  const std::vector<Claim> c = both_rule_claims(f, st);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].rule, StopRule::settled);  // "keeps oscillating" is about lasting behaviour
  EXPECT_EQ(c[0].paper, f[0].paper);
  EXPECT_EQ(c[0].measured,
            "settled rule: held in 40 of 1250 trials; first entry: held in 7 of 1250 trials");
  EXPECT_EQ(c[1].rule, StopRule::first_entry);
  EXPECT_EQ(c[1].measured, "held in 625 of 625 trials");  // the same under both: said once
}

}  // namespace
}  // namespace dampbound
