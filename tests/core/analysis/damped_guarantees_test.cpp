// What dampbound guarantees with SPEC 10's damping, each on the reproducer that once broke it:
// the exact verdict of every integrator with dashpots and Rayleigh damping, the damped safe
// bound against the exact limit, and the safe bound suggest quotes where dashpots act. Each
// verdict is checked against a run of the scene.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/suggest.hpp"
#include "core/io/scene_file.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound {
namespace {

SceneSpec shipped(const std::string& name) {
  return load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/" + name + ".toml");
}

RunResult run(const SceneSpec& scene, const Params& p) {
  Session s(scene, p, scene.rules);
  return s.run_to_end();
}

ExactStability exact_of(const SceneSpec& scene, const Params& p) {
  const Model model = compile_model(scene.model, p);
  return exact_stability(model, scene.model.rest, p);
}

struct IntegratorCase {
  Integrator integrator;
  double kd, alpha;
};

class DampedIntegrator : public ::testing::TestWithParam<IntegratorCase> {};

// bounds two-node --integrator forward-euler --kd 0.1 printed rho 0.95 and dt limit 1 s, both
// "within", from the nodal damping alone; the run diverges at iteration 10. The same for RK4
// with --rayleigh-mass 100 and Verlet with --kd 1.
TEST_P(DampedIntegrator, TheVerdictCountsTheDampingAndTheRunAgrees) {
  const IntegratorCase c = GetParam();
  const SceneSpec scene = shipped("two-node");
  Params p = scene.params;
  p.integrator = c.integrator;
  p.kd = c.kd;
  p.rayleigh_mass = c.alpha;
  const ExactStability e = exact_of(scene, p);
  EXPECT_EQ(e.method, ExactMethod::damped_radius);
  EXPECT_TRUE(e.spec10);
  EXPECT_FALSE(e.stable) << "rho " << e.spectral_radius;
  EXPECT_GT(e.spectral_radius, 1);
  EXPECT_TRUE(std::isnan(e.dt_max)) << "not computed for this damping, never a nodal number";
  EXPECT_TRUE(std::isnan(e.gamma_hi));
  EXPECT_EQ(run(scene, p).outcome, Outcome::diverged);
  // A hundredth of the damping is stable, and the run settles or stays bounded.
  p.kd /= 100;
  p.rayleigh_mass /= 100;
  const ExactStability light = exact_of(scene, p);
  EXPECT_TRUE(light.stable) << "rho " << light.spectral_radius;
  EXPECT_LE(light.spectral_radius, 1);
  EXPECT_NE(run(scene, p).outcome, Outcome::diverged);
}

INSTANTIATE_TEST_SUITE_P(
    Reproducers, DampedIntegrator,
    ::testing::Values(IntegratorCase{Integrator::forward_euler, 0.1, 0},
                      IntegratorCase{Integrator::rk4, 0, 100},
                      IntegratorCase{Integrator::verlet, 1, 0}));

TEST(DampedImplicitEuler, StaysUnconditionalWithoutQuotingANodalRadius) {
  const SceneSpec scene = shipped("two-node");
  Params p = scene.params;
  p.integrator = Integrator::implicit_euler;
  p.kd = 1;
  const ExactStability e = exact_of(scene, p);
  EXPECT_TRUE(e.stable);
  EXPECT_TRUE(std::isnan(e.spectral_radius));
  EXPECT_NE(run(scene, p).outcome, Outcome::diverged);
}

// bounds two-node --kappa 1e-20 --kd 0.002 --dt 0.6 printed a safe dt of 1 s beside the exact
// limit 0.5 s: the margin's root (-P + sqrt(P^2 + 16 Q)) / 2Q rounded to 0 and was dropped.
TEST(DampedSafeBound, NeverAboveTheExactLimitWhenTheStiffnessIsTiny) {
  const SceneSpec scene = shipped("two-node");
  Params p = scene.params;
  p.kappa = 1e-20;
  p.kd = 0.002;
  p.dt = 0.6;
  const Model model = compile_model(scene.model, p);
  const ExactStability e = exact_stability(model, scene.model.rest, p);
  const SafeBoundSummary s = safe_bound_summary(model, scene.model.rest, p.dt);
  ASSERT_TRUE(std::isfinite(e.dt_max));
  EXPECT_NEAR(e.dt_max, 0.5, 1e-6);  // 2 dt (gamma + kd) / m = 4 at gamma = kd = 0.002
  EXPECT_LE(s.dt_safe, e.dt_max * (1 + 1e-9));  // the exact limit is certified to 1e-10
  EXPECT_GT(s.dt_safe, 0.99 * e.dt_max);  // the dashpot dominates: Gershgorin is tight here
  EXPECT_FALSE(e.stable);                 // dt 0.6 > 0.5
}

// suggest quad-cloth-dashpots said "safe bound gamma < 0.039625 guarantees stability" from the
// nodal rows; the damped rows give 0.009625, and run --gamma 0.03 diverges at 15.
TEST(DampedSuggest, QuotesTheDampedSafeBound) {
  const SceneSpec scene = shipped("quad-cloth-dashpots");
  SuggestOptions quiet;
  quiet.verify = false;
  const DampingSuggestion d = suggest_damping(scene, scene.params, scene.rules, quiet);
  const Model model = compile_model(scene.model, scene.params);
  const SafeBoundSummary s = safe_bound_summary(model, scene.model.rest, scene.params.dt);
  EXPECT_DOUBLE_EQ(d.safe_max, s.gamma_safe);
  EXPECT_NEAR(d.safe_max, 0.009625, 1e-6);
  EXPECT_LE(d.safe_max, d.gamma_max);
  Params over = scene.params;
  over.gamma = 0.03;
  EXPECT_GT(over.gamma, d.safe_max);
  EXPECT_EQ(run(scene, over).outcome, Outcome::diverged);
  Params under = scene.params;
  under.gamma = 0.99 * d.safe_max;
  EXPECT_TRUE(exact_of(scene, under).stable);
}

}  // namespace
}  // namespace dampbound
