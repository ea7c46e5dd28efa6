// SPEC 9's safe bound as criteria rows (core/analysis/criteria_safe.hpp), on the two-node
// system, where Gershgorin's row sum is the one eigenvalue and the safe bounds are exact.
#include "core/analysis/criteria_safe.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/io/scene_file.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

struct TwoNode {
  SceneSpec scene = load_scene(test::source_path("scenes/two-node.toml"));
  Params params = scene.params;  // m = kappa = 0.001, gamma = 0.002, dt = 0.05
  Model model = compile_model(scene.model, params);
  State state = rest_state(model);
  void set(const Params& p) {
    params = p;
    model = compile_model(scene.model, params);
    state = rest_state(model);
  }
};

TEST(CriteriaSafe, TwoNodeAtRest) {
  const TwoNode t;
  const std::vector<CriterionResult> rows = safe_criteria(t.model, t.state, t.params);
  ASSERT_EQ(rows.size(), 3u);
  // R = kappa/m = 1 / s^2: gamma_safe = 2 m/dt - m dt R/2 = 0.04 - 0.000025.
  EXPECT_EQ(rows[0].name, "safe damping bound");
  EXPECT_NEAR(rows[0].value, 0.039975, 1e-15);
  EXPECT_EQ(rows[0].node, 1);
  EXPECT_EQ(rows[0].verdict, CriterionVerdict::within);
  EXPECT_EQ(rows[0].test.substr(0, 43), "0 of 1 node with gamma_i >= gamma_safe_i; s");
  // c = gamma/m = 2: dt_safe = (sqrt(c^2 + 4 R) - c)/R = 2 sqrt 2 - 2.
  EXPECT_EQ(rows[1].name, "safe dt bound");
  EXPECT_NEAR(rows[1].value, 2 * std::sqrt(2.0) - 2, 1e-15);
  EXPECT_EQ(rows[1].verdict, CriterionVerdict::within);
  EXPECT_EQ(rows[1].test.substr(0, 22), "dt = 0.05 < dt_safe = ");
  // gamma_lo = 2 sqrt(m kappa) = 0.002 <= gamma_safe.
  EXPECT_EQ(rows[2].value, 0.0);
  EXPECT_EQ(rows[2].verdict, CriterionVerdict::within);
  EXPECT_EQ(rows[2].test, "gamma_lo_i <= gamma_safe_i at every free node");
}

TEST(CriteriaSafe, RatiosToTheExactLimitsAreOneForASingleMode) {
  const TwoNode t;
  const ExactStability exact = exact_stability(t.model, t.state.x, t.params);
  const auto rows = safe_criteria(t.model, t.state, t.params, &exact);
  EXPECT_NE(rows[0].test.find("; 1 of the exact limit 0.039975"), std::string::npos)
      << rows[0].test;
  EXPECT_NE(rows[1].test.find("; 1 of the exact limit 0.828427"), std::string::npos)
      << rows[1].test;
}

TEST(CriteriaSafe, BeyondTheBounds) {
  TwoNode t;
  Params p = t.params;
  p.gamma = 0.05;  // above gamma_safe = 0.039975; c = 50: dt_safe = (sqrt(2504) - 50) < 0.05
  t.set(p);
  auto rows = safe_criteria(t.model, t.state, t.params);
  EXPECT_EQ(rows[0].verdict, CriterionVerdict::beyond);
  EXPECT_EQ(rows[0].test.substr(0, 12), "1 of 1 node ");
  EXPECT_NEAR(rows[1].value, std::sqrt(2504.0) - 50, 1e-12);
  EXPECT_EQ(rows[1].verdict, CriterionVerdict::beyond);
  EXPECT_EQ(rows[1].test.substr(0, 23), "dt = 0.05 >= dt_safe = ");
  // dt = 2: gamma_safe = 2 m/2 - m 2/2 = 0 < gamma_lo = 0.002: critical damping is not safe.
  p = t.params;
  p.dt = 2.0;
  t.set(p);
  rows = safe_criteria(t.model, t.state, t.params);
  EXPECT_NEAR(rows[0].value, 0.0, 1e-18);
  EXPECT_EQ(rows[2].value, 1.0);
  EXPECT_EQ(rows[2].node, 1);
  EXPECT_EQ(rows[2].verdict, CriterionVerdict::beyond);
  EXPECT_EQ(rows[2].test.substr(0, 51), "1 of 1 node with gamma_lo > gamma_safe (first: node");
}

TEST(CriteriaSafe, CompressedSpringGivesNoVerdict) {
  TwoNode t;
  t.state.x[1] = Vec3(0.5, 0, 0);  // l = 0.5 < l0 = 1
  const auto rows = safe_criteria(t.model, t.state, t.params);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].verdict, CriterionVerdict::not_applicable);
  EXPECT_EQ(rows[1].verdict, CriterionVerdict::not_applicable);
  // SPEC 9: no promise of critical damping either, though every gamma_lo_i <= gamma_safe_i.
  EXPECT_EQ(rows[2].value, 0.0);
  EXPECT_EQ(rows[2].verdict, CriterionVerdict::not_applicable);
  const std::string caveat = "; 1 compressed springs: K may not be positive semi-definite, no guarantee";
  for (const CriterionResult& r : rows)
    EXPECT_EQ(r.test.substr(r.test.size() - caveat.size()), caveat) << r.name;
}

TEST(CriteriaSafe, OnlyThePaperStepGetsAVerdict) {
  // Undamped, the two-node system is within every safe bound: SPEC 9 proves the paper's step
  // stable, but forward Euler grows at any dt (|1 + i dt omega| > 1). The rows must not say
  // "within" under an integrator SPEC 9 was not derived for.
  TwoNode t;
  Params p = t.params;
  p.gamma = 0;
  for (Integrator in : {Integrator::semi_implicit_euler, Integrator::forward_euler,
                        Integrator::verlet, Integrator::rk4, Integrator::implicit_euler}) {
    p.integrator = in;
    t.set(p);
    const auto rows = safe_criteria(t.model, t.state, t.params);
    ASSERT_EQ(rows.size(), 3u);
    const std::string scope = safe_bound_scope(in);
    for (const CriterionResult& r : rows) {
      if (in == Integrator::semi_implicit_euler) {
        EXPECT_EQ(r.verdict, CriterionVerdict::within) << r.name;
        EXPECT_TRUE(scope.empty());
      } else {
        EXPECT_EQ(r.verdict, CriterionVerdict::not_applicable) << to_string(in) << ' ' << r.name;
        ASSERT_GE(r.test.size(), scope.size());
        EXPECT_EQ(r.test.substr(r.test.size() - scope.size()), scope) << r.test;
        EXPECT_NE(scope.find(to_string(in)), std::string::npos);
      }
    }
    if (in == Integrator::forward_euler) {
      EXPECT_FALSE(exact_stability(t.model, t.state.x, t.params).stable);
    }
    if (in == Integrator::semi_implicit_euler) {
      EXPECT_TRUE(exact_stability(t.model, t.state.x, t.params).stable);
    }
  }
}

TEST(CriteriaSafe, NoFreeNodeNoRows) {
  TwoNode t;
  t.scene.model.fixed[1] = 1;
  t.set(t.params);
  EXPECT_TRUE(safe_criteria(t.model, t.state, t.params).empty());
}

}  // namespace
}  // namespace dampbound
