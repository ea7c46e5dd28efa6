// The Suggest tab's stiffness ceiling and Rayleigh pair (ui/tuner_knobs.hpp): core's answers
// computed on the worker, the apply buttons' parameters checked against an independent
// computation, Cancel through the core's progress hook, and when a result stops speaking for
// the model.
#include "ui/tuner_knobs.hpp"
#include "ui/tuner_substeps.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/suggest.hpp"
#include "dampbound/run/scene.hpp"
#include "ui/tuner.hpp"
#include "tests/ui/ui_test_util.hpp"

namespace dampbound::ui {
namespace {

using ui_test::small_plane;

KnobsResult computed(const SceneSpec& scene, const Params& p, double zeta) {
  TunerKnobs k;
  k.start(scene, p, scene.rules, zeta);
  k.job().wait();
  EXPECT_TRUE(k.job().error().empty()) << k.job().error();
  return k.job().result().value_or(KnobsResult{});
}

TEST(TunerKnobs, GivesCoresCeilingAndPairWithTheirRuns) {
  const SceneSpec scene = small_plane(8, 400);
  const KnobsResult r = computed(scene, scene.params, 0.05);
  const StiffnessCeiling want =
      stiffness_ceiling(scene, scene.params, whole_selection(scene.model), scene.rules, true);
  EXPECT_TRUE(r.ceiling_error.empty()) << r.ceiling_error;
  EXPECT_EQ(r.ceiling.factor, want.factor);
  EXPECT_GT(r.ceiling.factor, 1.0);
  ASSERT_TRUE(r.ceiling.ran);
  EXPECT_EQ(r.ceiling.below.result.outcome, want.below.result.outcome);
  EXPECT_EQ(r.ceiling.above.result.iterations, want.above.result.iterations);
  EXPECT_TRUE(r.ceiling.below.verified());
  RayleighRequest q;
  q.zeta1 = q.zeta2 = 0.05;
  const RayleighDesign d = rayleigh_from_spectrum(scene, scene.params, q);
  ASSERT_TRUE(r.rayleigh.has_value()) << r.rayleigh_error;
  EXPECT_EQ(r.rayleigh->alpha, d.alpha);
  EXPECT_EQ(r.rayleigh->beta, d.beta);
  EXPECT_EQ(r.rayleigh->stable, d.stable);
}

// Apply kappa: 0.98 x the ceiling. Independently, the ceiling computed again at the applied
// kappa is 1 / 0.98 (the index is what the factor scales), and the exact analysis of the
// applied parameters is stable while 1.02 x the ceiling is not.
TEST(TunerKnobs, ApplyingTheCeilingLeavesTwoPercentOfMargin) {
  const SceneSpec scene = small_plane(8, 400);
  const KnobsResult r = computed(scene, scene.params, 0.05);
  const auto p = with_kappa_ceiling(scene.params, r);
  ASSERT_TRUE(p.has_value());
  EXPECT_DOUBLE_EQ(p->kappa, kCeilingMargin * r.ceiling.factor * scene.params.kappa);
  EXPECT_EQ(p->gamma, scene.params.gamma);  // gamma held, as the ceiling assumes
  const StiffnessCeiling again =
      stiffness_ceiling(scene, *p, whole_selection(scene.model), scene.rules, false);
  EXPECT_NEAR(again.factor, 1 / kCeilingMargin, 1e-6);
  const auto exact_stable = [&](const Params& q) {
    const Model m = compile_model(scene.model, q);
    return exact_stability(m, m.spec().rest, q).stable;
  };
  EXPECT_TRUE(exact_stable(*p));
  Params over = scene.params;
  over.kappa = 1.02 * r.ceiling.factor * scene.params.kappa;
  EXPECT_FALSE(exact_stable(over));
}

// Apply alpha, beta: the pair's ratios come back from the spectrum at both frequencies.
TEST(TunerKnobs, ApplyingThePairSetsAlphaAndBeta) {
  const SceneSpec scene = small_plane(8, 400);
  const KnobsResult r = computed(scene, scene.params, 0.1);
  const auto p = with_rayleigh_pair(scene.params, r);
  ASSERT_TRUE(p.has_value()) << r.rayleigh_error;
  EXPECT_EQ(p->rayleigh_mass, r.rayleigh->alpha);
  EXPECT_EQ(p->rayleigh_stiffness, r.rayleigh->beta);
  EXPECT_NEAR(rayleigh_zeta(p->rayleigh_mass, p->rayleigh_stiffness, r.rayleigh->f1), 0.1, 1e-9);
  EXPECT_NEAR(rayleigh_zeta(p->rayleigh_mass, p->rayleigh_stiffness, r.rayleigh->f2), 0.1, 1e-9);
  KnobsResult none = r;
  none.rayleigh->feasible = false;
  EXPECT_FALSE(with_rayleigh_pair(scene.params, none).has_value());
  none.rayleigh.reset();
  EXPECT_FALSE(with_rayleigh_pair(scene.params, none).has_value());
  KnobsResult no_ceiling = r;
  no_ceiling.ceiling.factor = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(with_kappa_ceiling(scene.params, no_ceiling).has_value());
}

// The core's progress hook names each stage, and false stops the call (the tab's Cancel).
TEST(TunerKnobs, TheCoreSaysEachStageAndStopsWhenAsked) {
  const SceneSpec scene = small_plane(8, 400);
  std::vector<std::string> stages;
  const auto note = [&](const std::string& s) {
    stages.push_back(s);
    return true;
  };
  stiffness_ceiling(scene, scene.params, whole_selection(scene.model), scene.rules, true, note);
  ASSERT_EQ(stages.size(), 4u);
  EXPECT_NE(stages[1].find("bisection"), std::string::npos);
  EXPECT_NE(stages[3].find("run 2 of 2"), std::string::npos);
  stages.clear();
  rayleigh_from_spectrum(scene, scene.params, RayleighRequest{}, note);
  ASSERT_EQ(stages.size(), 3u);
  EXPECT_NE(stages[0].find("stage 1 of 3"), std::string::npos);
  const auto stop = [](const std::string&) { return false; };
  EXPECT_THROW(stiffness_ceiling(scene, scene.params, whole_selection(scene.model), scene.rules,
                                 true, stop),
               SuggestCancelled);
  EXPECT_THROW(rayleigh_from_spectrum(scene, scene.params, RayleighRequest{}, stop),
               SuggestCancelled);
}

TEST(TunerKnobs, CancelDropsTheComputation) {
  const SceneSpec scene = small_plane(8, 400);
  TunerKnobs k;
  k.start(scene, scene.params, scene.rules, 0.05);
  EXPECT_TRUE(k.job().busy());
  k.job().cancel();
  EXPECT_FALSE(k.job().busy());
  EXPECT_TRUE(k.job().cancelled());
  k.job().wait();
  EXPECT_FALSE(k.job().result().has_value());
}

// A result speaks for the parameters and springs it was computed for: a parameter change, a
// reset, a cut or another scene makes it stale (the tab then drops it).
// The tuner's --factor-budget reaches the ceiling and the pair (and the substep count's mass
// scaling): over it each part says so instead of factorising unbounded.
TEST(TunerKnobs, TheFactorisationBudgetReachesTheCeilingAndThePair) {
  const SceneSpec scene = small_plane(24, 400);  // 1728 rows: sparse factorisations
  TunerKnobs k;
  k.set_factor_budget(1e3);
  k.start(scene, scene.params, scene.rules, 0.05);
  k.job().wait();
  ASSERT_TRUE(k.job().result());
  EXPECT_NE(k.job().result()->ceiling_error.find("over the budget"), std::string::npos)
      << k.job().result()->ceiling_error;
  EXPECT_NE(k.job().result()->rayleigh_error.find("over the budget"), std::string::npos)
      << k.job().result()->rayleigh_error;
  TunerSubsteps s;
  s.set_factor_budget(1e3);
  s.start(scene, scene.params, scene.rules, 2.0);
  s.job().wait();
  ASSERT_TRUE(s.job().result()) << s.job().error();
  EXPECT_FALSE(s.job().result()->mass);
  EXPECT_NE(s.job().result()->mass_error.find("over the budget"), std::string::npos)
      << s.job().result()->mass_error;
  EXPECT_NE(s.job().result()->substeps.note.find("not computed"), std::string::npos)
      << s.job().result()->substeps.note;
}

TEST(TunerKnobs, AResultIsCurrentOnlyForItsModel) {
  Tuner t(small_plane(8, 400));
  TunerKnobs k;
  const auto start = [&] {
    k.job().clear();
    k.start(t.session(), 0.05, t.generation(), t.topology());
    k.job().wait();
  };
  const auto current = [&] { return k.current(t.params(), t.generation(), t.topology()); };
  start();
  ASSERT_TRUE(k.job().result().has_value()) << k.job().error();
  EXPECT_TRUE(current());
  t.step(3);
  EXPECT_TRUE(current()) << "stepping changes no parameter and no spring";
  Params p = t.params();
  p.kappa *= 2;
  ASSERT_TRUE(t.set_params(p));
  EXPECT_FALSE(current()) << "kappa changed";
  start();
  p = t.params();
  p.rayleigh_mass = 0.01;
  ASSERT_TRUE(t.set_params(p));
  EXPECT_FALSE(current()) << "alpha changed";
  start();
  t.reset();
  EXPECT_FALSE(current()) << "reset";
  start();
  ASSERT_GT(t.cut({0, 1}), 0);
  EXPECT_FALSE(current()) << "a cut";
  start();
  t.set_scene(small_plane(8, 400));
  EXPECT_FALSE(current()) << "another scene";
}

}  // namespace
}  // namespace dampbound::ui
