// Scene expectations (core/analysis/expect.hpp): which run is judged, and every field judged
// pass or fail against the run's result, with the measured value in words.
#include "core/analysis/expect.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/io/scene_file.hpp"
#include "dampbound/run/session.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

SceneSpec two_node() { return load_scene(test::source_path("scenes/two-node.toml")); }

TEST(Expect, RunLabelledPicksTheRunsParametersAndRule) {
  SceneSpec s = two_node();
  s.rules.rule = StopRule::first_entry;  // run_labelled's rule when none is given
  RunSpec soft;
  soft.label = "soft";
  soft.params = s.params;
  soft.params.gamma = 0.0002;  // a tenth of critical
  soft.rules = s.rules;
  s.runs.push_back(soft);
  const RunResult own = run_labelled(s, "");
  Session direct(s, s.params, s.rules);
  const RunResult by_hand = direct.run_to_end();
  EXPECT_EQ(own.outcome, by_hand.outcome);
  EXPECT_EQ(own.iterations, by_hand.iterations);
  EXPECT_EQ(own.outcome, Outcome::restored);  // critical damping restores the pull
  const RunResult ringing = run_labelled(s, "soft");
  Session soft_session(s, soft.params, soft.rules);
  EXPECT_EQ(ringing.iterations, soft_session.run_to_end().iterations);
  EXPECT_NE(ringing.iterations, own.iterations);  // it swings through the band sooner
  // The settled rule steps to the limit.
  const RunResult settled = run_labelled(s, "", StopRule::settled);
  EXPECT_EQ(settled.outcome, Outcome::settled);
  EXPECT_EQ(settled.iterations, s.rules.max_iterations);
  EXPECT_EQ(settled.first_entry, own.first_entry);
}

TEST(Expect, NoExpectationsNoResults) {
  EXPECT_TRUE(check_expectations(two_node()).empty());
}

TEST(Expect, EachFieldIsJudged) {
  SceneSpec s = two_node();
  const RunResult r = run_labelled(s, "");
  const int n = r.iterations;
  Expectation pass;
  pass.rule = StopRule::first_entry;  // the default is settled
  pass.line = 40;
  pass.outcome = Outcome::restored;
  pass.iterations_min = n, pass.iterations_max = n;
  pass.first_entry_min = 1, pass.first_entry_max = n;
  pass.left = false;
  pass.max_displacement_below = 0.005;  // restored: below 1% of the 0.5 cm pull
  pass.violations_max = 0;
  pass.unstabilisable_max = 0;
  Expectation fail;
  fail.rule = StopRule::first_entry;
  fail.line = 41;
  fail.outcome = Outcome::diverged;
  fail.iterations_min = n + 1, fail.iterations_max = n + 10;
  fail.settled_at_min = 1, fail.settled_at_max = 1000;  // none under the first-entry rule
  fail.left = true;
  fail.violations_min = 1;
  s.expectations = {pass, fail};
  const std::vector<ExpectationResult> out = check_expectations(s);
  ASSERT_EQ(out.size(), 7u + 5u);
  for (size_t k = 0; k < 7; ++k) {
    SCOPED_TRACE(out[k].what);
    EXPECT_TRUE(out[k].pass);
    EXPECT_EQ(out[k].line, 40);
    EXPECT_EQ(out[k].scene, s.path);
    EXPECT_EQ(out[k].run, "");
  }
  for (size_t k = 7; k < out.size(); ++k) {
    SCOPED_TRACE(out[k].what);
    EXPECT_FALSE(out[k].pass);
    EXPECT_EQ(out[k].line, 41);
  }
  const std::string ns = std::to_string(n);
  EXPECT_EQ(out[0].what, "[first-entry] outcome == restored");
  EXPECT_EQ(out[1].what, "[first-entry] iterations in [" + ns + ", " + ns + "]");
  EXPECT_EQ(out[1].measured, ns);
  EXPECT_EQ(out[3].what, "[first-entry] left == false");
  EXPECT_EQ(out[3].measured, "never left");
  EXPECT_EQ(out[5].what, "[first-entry] unstabilisable node-steps <= 0");
  EXPECT_EQ(out[6].what, "[first-entry] violating node-steps <= 0");
  EXPECT_EQ(out[6].measured, "0");
  EXPECT_EQ(out[7].what, "[first-entry] outcome == diverged");
  EXPECT_EQ(out[9].what, "[first-entry] left == true");
  EXPECT_EQ(out[10].what, "[first-entry] settled_at in [1, 1000]");
  EXPECT_EQ(out[10].measured, "none");  // 0 is outside every range
  EXPECT_EQ(out[11].what, "[first-entry] violating node-steps >= 1");
}


// dt_limit_min and substeps_max against the two-node system's closed form: one free node on one
// spring, lambda = kappa/m = 1/s^2, c = gamma/m = 2/s, stable for dt^2 + 4 dt - 4 < 0 (SPEC 7),
// dt < 2 sqrt(2) - 2 = 0.8284 s, so a frame of 1 s needs 2 substeps. No run is made.
TEST(Expect, LimitsAreJudgedByTheExactAnalysis) {
  SceneSpec s = two_node();
  const double limit = 2 * std::sqrt(2.0) - 2;
  Expectation pass, fail;
  pass.dt_limit_min = limit * (1 - 1e-6);
  pass.substeps_max = 2;
  pass.frame_dt = 1.0;
  fail.dt_limit_min = limit * (1 + 1e-6);
  fail.substeps_max = 1;
  fail.frame_dt = 1.0;
  s.expectations = {pass, fail};
  const std::vector<ExpectationResult> r = check_expectations(s);
  ASSERT_EQ(r.size(), 4u);
  EXPECT_TRUE(r[0].pass) << r[0].what << " " << r[0].measured;
  EXPECT_TRUE(r[1].pass) << r[1].what << " " << r[1].measured;
  EXPECT_FALSE(r[2].pass);
  EXPECT_FALSE(r[3].pass);
  EXPECT_EQ(r[1].measured.substr(0, 2), "2 ");
  EXPECT_NE(r[0].measured.find("0.82842712"), std::string::npos) << r[0].measured;
}

}  // namespace
}  // namespace dampbound

namespace dampbound {
namespace {

/// SPEC 11's plane as a scene file, with mass scaling expectations for dt* = 0.3 s.
const char* kMassScaled = R"(
[grid]
nx = 8
nz = 8
spacing = 0.57
[[region]]
min = [1.7, -1.0, 1.7]
max = [2.3, 1.0, 2.3]
mass_scale = 0.1
[[region]]
min = [0.0, 0.0, 0.0]
max = [0.0, 0.0, 0.0]
fixed = true
[params]
m = 0.001
kappa = 0.001
gamma = 0.002
dt = 0.05
[[perturb]]
node = [4, 4]
displacement = [0.0, 5.0, 0.0]
[[expect]]
mass_scale_dt = 0.3
added_mass_percent = [2.7, 2.85]
scaled_nodes = [4, 4]
outcome = "settled"
[[expect]]
mass_scale_dt = 0.3
added_mass_percent = [3.0, 3.5]
)";

TEST(Expect, MassScaleExpectationsJudgeTheAnswerAndTheRunWithTheScaledMasses) {
  const SceneSpec s = parse_scene(kMassScaled, "mass.toml");
  ASSERT_EQ(s.expectations.size(), 2u);
  EXPECT_EQ(*s.expectations[0].mass_scale_dt, 0.3);
  const std::vector<ExpectationResult> out = check_expectations(s);
  ASSERT_EQ(out.size(), 4u);
  for (size_t k = 0; k < 3; ++k) EXPECT_TRUE(out[k].pass) << out[k].what << ": " << out[k].measured;
  EXPECT_FALSE(out[3].pass) << out[3].measured;  // 2.77 %, not in [3, 3.5]
  EXPECT_NE(out[0].what.find("mass scaled for dt* = 0.3"), std::string::npos) << out[0].what;
}

TEST(Expect, MassScaleKeysNeedTheirTargetAndTheSettledRule) {
  const std::string base = std::string(kMassScaled).substr(0, std::string(kMassScaled).find("[[expect]]"));
  EXPECT_NE(test::input_error([&] {
              parse_scene(base + "[[expect]]\nadded_mass_percent = [1.0, 2.0]\n", "m.toml");
            }).find("needs mass_scale_dt"),
            std::string::npos);
  EXPECT_NE(test::input_error([&] {
              parse_scene(base + "[[expect]]\nrule = \"first-entry\"\nmass_scale_dt = 0.3\n"
                                 "scaled_nodes = [1, 2]\n",
                          "m.toml");
            }).find("settled"),
            std::string::npos);
}

}  // namespace
}  // namespace dampbound
