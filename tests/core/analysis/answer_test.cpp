// The answer-first lines: their verdict and numbers are the analysis's and the run's own.
#include "core/analysis/answer.hpp"

#include <gtest/gtest.h>

#include "core/analysis/criteria.hpp"
#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/run/session.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

Params two_node_at(double gamma, double dt) {
  Params p;
  p.m = 0.001, p.kappa = 0.001, p.gamma = gamma, p.dt = dt;
  return p;
}

bool has(const std::vector<std::string>& lines, const std::string& text) {
  for (const std::string& l : lines)
    if (l.find(text) != std::string::npos) return true;
  return false;
}

TEST(Answer, AStableStepSaysItsLimitsFromTheAnalysis) {
  const Params p = two_node_at(0.002, 0.05);
  const Model model = two_node_system(p);
  const State rest = rest_state(model);
  const ExactStability e = exact_stability(model, rest.x, p);
  ASSERT_TRUE(e.stable);
  const SafeBoundSummary safe = safe_bound_summary(model, rest.x, p.dt);
  const auto lines = exact_answer(e, &p, &safe, "at rest");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].rfind("stable at gamma = 0.002, dt = 0.05 s (exact linear analysis at rest", 0), 0u)
      << lines[0];
  EXPECT_TRUE(has(lines, "dt < " + format_human(e.dt_max) + " s at this gamma")) << lines[1];
  EXPECT_TRUE(has(lines, "gamma in [" + format_human(e.gamma_lo) + ", " + format_human(e.gamma_hi) + ")"));
  EXPECT_TRUE(has(lines, "gamma < " + format_human(safe.gamma_safe)));
}

TEST(Answer, AnUnstableStepSaysWhatToChange) {
  const Params stable = two_node_at(0.002, 0.05);
  const Model model = two_node_system(stable);
  const ExactStability at_stable = exact_stability(model, rest_state(model).x, stable);
  // Twice the largest stable dt: the analysis itself says unstable there.
  const Params p = two_node_at(0.002, 2 * at_stable.dt_max);
  const Model big = two_node_system(p);
  const ExactStability e = exact_stability(big, rest_state(big).x, p);
  ASSERT_FALSE(e.stable);
  const auto lines = exact_answer(e, &p, nullptr, "at rest");
  EXPECT_EQ(lines[0].rfind("UNSTABLE at gamma = 0.002", 0), 0u) << lines[0];
  EXPECT_TRUE(has(lines, "to fix: dt < " + format_human(e.dt_max) + " s at this gamma")) << lines[1];
}

TEST(Answer, ARunSaysItsVerdictAndWhatToTry) {
  SceneSpec scene = load_scene(test::source_path("scenes/two-node.toml"));
  Params p = scene.params;
  StopRules rules = scene.rules;
  rules.rule = StopRule::settled;
  Session ok(scene, p, rules);
  const RunResult& r = ok.run_to_end();
  auto lines = run_answer(r, rules, p);
  EXPECT_EQ(lines[0].rfind(verdict_text(r, rules), 0), 0u) << lines[0];
  EXPECT_EQ(lines.size(), r.outcome == Outcome::settled ? 1u : 2u);
  p.dt = 5;  // far past the limit: diverges
  Session bad(scene, p, rules);
  const RunResult& d = bad.run_to_end();
  ASSERT_EQ(d.outcome, Outcome::diverged);
  lines = run_answer(d, rules, p);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[1].find("lower dt"), std::string::npos);
}

}  // namespace
}  // namespace dampbound
