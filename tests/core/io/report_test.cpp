// Traces and results as text (core/io/report.hpp): the CSV rows, the verdicts in words and
// the JSON object.
#include "core/io/report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace dampbound {
namespace {

const char* kHeader =
    "iteration,time,displacement,lower_bound,upper_bound,gamma,gamma_effective,zeta,zeta_effective,"
    "max_displacement,violating,unstabilisable,clamped,zero_length_springs,"
    "safe_bound,unguaranteed,compressed_springs\n";

StepSample row(int it) {
  StepSample s;
  s.iteration = it;
  s.time = 0.05 * it;
  s.watched.displacement = 0.5;
  s.watched.lower = 0.002;
  s.watched.upper = std::numeric_limits<double>::infinity();
  s.watched.gamma = 0.001;
  s.watched.gamma_eff = 0.001;
  s.max_displacement = 0.25;
  s.violating = 1;
  s.unstabilisable = 2;
  s.clamped = 3;
  s.zero_length_springs = 4;
  s.watched.safe = std::nan("");
  s.unguaranteed = 5;
  s.compressed_springs = 6;
  return s;
}

TEST(Report, TraceCsvRows) {
  std::ostringstream out;
  write_trace_csv(out, {row(1), row(2)});
  EXPECT_EQ(out.str(), std::string(kHeader) +
                           "1,0.05,0.5,0.002,inf,0.001,0.001,0.5,0.5,0.25,1,2,3,4,inf,5,6\n"
                           "2,0.1,0.5,0.002,inf,0.001,0.001,0.5,0.5,0.25,1,2,3,4,inf,5,6\n");
}

TEST(Report, TraceCsvWithARunLabel) {
  std::ostringstream out;
  write_trace_csv(out, {row(3)}, "gamma 0.5, upper");
  EXPECT_EQ(out.str().substr(0, 14), "run,iteration,");
  EXPECT_NE(out.str().find("\n\"gamma 0.5, upper\",3,"), std::string::npos);  // quoted: a comma
  std::ostringstream plain;
  write_trace_csv(plain, {row(3)}, "say \"hi\"", false);
  EXPECT_EQ(plain.str().substr(0, 15), "\"say \"\"hi\"\"\",3,");  // quotes doubled
  std::ostringstream cr;
  write_trace_csv(cr, {row(3)}, "a\rb", false);
  EXPECT_EQ(cr.str().substr(0, 8), "\"a\rb\",3,");  // a bare CR is a line break too
}

TEST(Report, VerdictsInWords) {
  StopRules rules;
  rules.rule = StopRule::first_entry;
  rules.max_iterations = 1000;
  RunResult r;
  EXPECT_EQ(verdict_text(r, rules), "running");
  EXPECT_EQ(verdict_short(r), "running");
  r.outcome = Outcome::restored, r.iterations = 112, r.first_entry = 112;
  EXPECT_EQ(verdict_text(r, rules), "restored at 112 (first entry into the 1% band, the paper's rule)");
  EXPECT_EQ(verdict_short(r), "restored at 112");
  r = RunResult{};
  r.outcome = Outcome::not_settled, r.iterations = 1000, r.first_entry = 12, r.left_at = 63;
  EXPECT_EQ(verdict_text(r, rules),
            "not settled, checked to 1000 (entered the 1% band at 12, left it at 63)");
  EXPECT_EQ(verdict_short(r), "not settled at 1000 (entered at 12, left at 63)");
  r = RunResult{};
  r.outcome = Outcome::settled, r.iterations = 1000, r.first_entry = 230, r.left_at = 231;
  r.settled_at = 260;
  EXPECT_EQ(verdict_text(r, rules),
            "settled at 260, checked to 1000 (entered the 1% band at 230, left it at 231)");
  r.left_at = 0, r.first_entry = r.settled_at;
  EXPECT_EQ(verdict_text(r, rules), "settled at 260, checked to 1000");
  EXPECT_EQ(verdict_short(r), "settled at 260");
  r.iterations = 296;  // stopped by SPEC 8's proof (docs/settled.md)
  EXPECT_EQ(verdict_text(r, rules), "settled at 260, proven at 296 to stay to 1000");
  r = RunResult{};
  r.outcome = Outcome::not_settled, r.iterations = 1000;
  EXPECT_EQ(verdict_text(r, rules), "not settled, checked to 1000 (never entered the 1% band)");
  EXPECT_EQ(verdict_short(r), "not settled at 1000");
  r = RunResult{};
  r.outcome = Outcome::diverged, r.iterations = 40;
  EXPECT_EQ(verdict_text(r, rules), "diverged at 40");
  EXPECT_EQ(verdict_short(r), "diverged at 40");
  r.outcome = Outcome::not_restored, r.iterations = 1000;
  rules.restore_fraction = 0.025;
  EXPECT_EQ(verdict_text(r, rules), "not restored, checked to 1000 (the paper's rule)");
  EXPECT_EQ(verdict_short(r), "not restored at 1000");
  r = RunResult{};  // still running, back in the band after leaving it
  r.first_entry = 5, r.left_at = 9, r.below_since = 14;
  EXPECT_EQ(verdict_text(r, rules),
            "running: entered the 2.5% band at 5, left it at 9, back in since 14");
  EXPECT_EQ(verdict_short(r), "running (entered at 5, left at 9)");
}

TEST(Report, ResultJson) {
  Params p;
  p.m = 0.001, p.kappa = 0.001, p.gamma = 0.002, p.dt = 0.05;
  p.policy = DampingPolicy::fixed;
  StopRules rules;
  rules.rule = StopRule::first_entry;
  rules.max_iterations = 1000;
  RunResult r;
  r.outcome = Outcome::restored, r.iterations = 34, r.first_entry = 34, r.time = 1.7;
  r.max_displacement = 0.004;
  const std::string j = result_json("two-node", p, rules, 1, r);
  const std::string head = "{\"scene\":\"two-node\",\"m\":0.001,\"kappa\":0.001,\"gamma\":0.002,";
  EXPECT_EQ(j.substr(0, head.size()), head);
  EXPECT_NE(j.find(",\"policy\":\"fixed\","), std::string::npos);
  // Every parameter that shaped the run, SPEC 10's damping and the band included.
  for (const char* key : {"\"kd\":0,", "\"rayleigh_mass\":0,", "\"rayleigh_stiffness\":0,",
                          "\"reference\":", "\"restore_fraction\":", "\"diverge_factor\":"})
    EXPECT_NE(j.find(key), std::string::npos) << key << " in " << j;
  EXPECT_NE(j.find(",\"max_iterations\":1000,\"watched\":1,\"outcome\":\"restored\","
                   "\"iterations\":34,\"rule\":\"first-entry\",\"first_entry\":34,"
                   "\"left_at\":null,\"settled_at\":null,\"time\":1.7,"
                   "\"max_displacement\":0.004,\"violations\":0,"),
            std::string::npos)
      << j;
  const std::string tail = "\"unguaranteed\":0,\"compressed_springs\":0}";
  EXPECT_EQ(j.substr(j.size() - tail.size()), tail);
}

// A zeta range prints as a range only where its ends read differently (zeta = 1 resolved at
// each node gives ratios a rounding apart: "1", not "1..1").
TEST(ZetaText, OneNumberWhereBothEndsReadAlike) {
  EXPECT_EQ(zeta_text(DampingRatioRange{1.0, std::nextafter(1.0, 2.0)}), "1");
  EXPECT_EQ(zeta_text(DampingRatioRange{0.5, 0.5}), "0.5");
  EXPECT_EQ(zeta_text(DampingRatioRange{0.5, 2.0}), "0.5..2");
  EXPECT_EQ(zeta_text(DampingRatioRange{std::nan(""), std::nan("")}), "none");
}

}  // namespace
}  // namespace dampbound
