// The [[expect]] tables of a scene file (core/io/detail/scene_expect.hpp), read through
// parse_scene (the private header pulls in toml++): every field, the rule's own verdicts, and
// the errors naming the line.
#include "core/io/scene_file.hpp"

#include <gtest/gtest.h>

#include "dampbound/physics/error.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

const std::string kScene =
    "[grid]\nnx = 3\nnz = 3\nspacing = 1.0\n"  // lines 1-4
    "[[run]]\nlabel = \"soft\"\ngamma = 0.0005\n";  // lines 5-7

std::string error_of(const std::string& expect) {
  return test::input_error([&] { parse_scene(kScene + expect, "e.toml"); });
}

TEST(SceneExpect, EveryField) {
  const SceneSpec s = parse_scene(kScene + R"([[expect]]
run = "soft"
rule = "settled"
outcome = "not_settled"
iterations = [1000, 1000]
first_entry = [0, 40]
left = true
left_at = [5, 50]
settled_at = [0, 0]
max_displacement_below = 2.5
unstabilisable_max = 0
violations_max = 7
violations_min = 3
[[expect]]
outcome = "diverged"
)",
                                  "e.toml");
  ASSERT_EQ(s.expectations.size(), 2u);
  const Expectation& x = s.expectations[0];
  EXPECT_EQ(x.line, 8);
  EXPECT_EQ(x.run, "soft");
  EXPECT_EQ(x.rule, StopRule::settled);
  EXPECT_EQ(*x.outcome, Outcome::not_settled);
  EXPECT_EQ(*x.iterations_min, 1000);
  EXPECT_EQ(*x.iterations_max, 1000);
  EXPECT_EQ(*x.first_entry_min, 0);
  EXPECT_EQ(*x.first_entry_max, 40);
  EXPECT_TRUE(*x.left);
  EXPECT_EQ(*x.left_at_min, 5);
  EXPECT_EQ(*x.left_at_max, 50);
  EXPECT_EQ(*x.settled_at_max, 0);
  EXPECT_EQ(*x.max_displacement_below, 2.5);
  EXPECT_EQ(*x.unstabilisable_max, 0);
  EXPECT_EQ(*x.violations_max, 7);
  EXPECT_EQ(*x.violations_min, 3);
  const Expectation& y = s.expectations[1];
  EXPECT_EQ(y.line, 21);
  EXPECT_EQ(y.run, "");
  EXPECT_EQ(y.rule, StopRule::settled);  // the default rule unless asked
  EXPECT_EQ(*y.outcome, Outcome::diverged);  // both rules' verdict
  EXPECT_FALSE(y.iterations_min.has_value());
  EXPECT_FALSE(y.left.has_value());
}

TEST(SceneExpect, EachRuleHasItsOwnVerdicts) {
  // Without a rule an expectation is judged by the default, settled.
  EXPECT_EQ(error_of("[[expect]]\noutcome = \"restored\"\n"),
            "e.toml:9: outcome must be settled, diverged or not_settled under rule settled "
            "(give rule = \"first-entry\" for restored, not_restored)");
  EXPECT_EQ(error_of("[[expect]]\nrule = \"first-entry\"\noutcome = \"settled\"\n"),
            "e.toml:10: outcome must be restored, diverged or not_restored under rule "
            "first-entry (give rule = \"settled\" for settled, not_settled)");
  EXPECT_EQ(error_of("[[expect]]\nrule = \"settled\"\noutcome = \"restored\"\n"),
            "e.toml:10: outcome must be settled, diverged or not_settled under rule settled "
            "(give rule = \"first-entry\" for restored, not_restored)");
  EXPECT_EQ(error_of("[[expect]]\nrule = \"last\"\n"), "e.toml:9: rule must be first-entry or settled");
  EXPECT_EQ(error_of("[[expect]]\nrule = \"first-entry\"\nleft = false\n"),
            "e.toml:10: left needs rule = \"settled\" (the first-entry rule stops at the entry)");
  EXPECT_EQ(error_of("[[expect]]\nrule = \"first-entry\"\nsettled_at = [1, 2]\n"),
            "e.toml:10: settled_at needs rule = \"settled\" (the first-entry rule stops at the "
            "entry)");
}

TEST(SceneExpect, RangesAndCounts) {
  EXPECT_EQ(error_of("[[expect]]\niterations = [5]\n"), "e.toml:9: iterations must be [min, max]");
  EXPECT_EQ(error_of("[[expect]]\niterations = [9, 5]\n"), "e.toml:9: iterations range is inverted");
  EXPECT_EQ(error_of("[[expect]]\niterations = [-1, 5]\n"),
            "e.toml:9: iterations must lie in 0..100000000");
  EXPECT_EQ(error_of("[[expect]]\nfirst_entry = [1, 100000001]\n"),
            "e.toml:9: first_entry must lie in 0..100000000");
  EXPECT_EQ(error_of("[[expect]]\nviolations_max = 1e19\n"),
            "e.toml:9: violations_max must be at most 1e18");
  EXPECT_NE(error_of("[[expect]]\nviolations_min = -1\n").find("e.toml:9: violations_min"),
            std::string::npos);
  EXPECT_NE(error_of("[[expect]]\nmax_displacement_below = 0\n").find("e.toml:9: "),
            std::string::npos);
}

TEST(SceneExpect, AnExpectationMustAssertSomething) {
  EXPECT_EQ(error_of("[[expect]]\nrun = \"soft\"\n"),
            "e.toml:8: [[expect]] asserts nothing: give outcome, iterations, first_entry, left, "
            "left_at, settled_at, max_displacement_below, unstabilisable_max, violations_max, "
            "violations_min, added_mass_percent, scaled_nodes, dt_limit_min or substeps_max");
  EXPECT_NE(error_of("[[expect]]\nframe_dt = 0.1\ndt_limit_min = 0.1\n").find("frame_dt goes with substeps_max"),
            std::string::npos);
  EXPECT_NE(error_of("[[expect]]\nsubsteps_max = 0\n").find("e.toml:9: substeps_max must lie in"),
            std::string::npos);
  EXPECT_EQ(error_of("[[expect]]\nrun = \"hard\"\noutcome = \"restored\"\n"),
            "e.toml:9: expect refers to run 'hard', which is not declared");
  EXPECT_EQ(error_of("[[expect]]\noutcome = \"settled\"\ncolour = 1\n"),
            "e.toml:10: unknown key 'colour' in [[expect]]");
}

}  // namespace
}  // namespace dampbound
