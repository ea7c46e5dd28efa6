// The Suggest tab's substeps per frame (ui/tuner_substeps.hpp): the counts of core's
// suggest_substeps, each verified on the worker, Cancel, and the apply button's dt.
#include "ui/tuner_substeps.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "dampbound/run/scene.hpp"
#include "ui/tuner.hpp"
#include "tests/ui/ui_test_util.hpp"

namespace dampbound::ui {
namespace {

using ui_test::small_plane;

// A frame of 2 s on the paper plane (exact dt limit about 0.5 s at gamma 0.002) needs
// several substeps: the worker gives core's counts and a settled run for each.
TEST(TunerSubsteps, GivesCoresCountsEachVerifiedByARun) {
  const SceneSpec scene = small_plane(8, 400);
  const double frame = 2.0;
  const SubstepSuggestion want = suggest_substeps(scene, scene.params, scene.rules, frame);
  ASSERT_GT(want.exact.n, 1);
  ASSERT_GE(want.safe.n, want.exact.n);
  TunerSubsteps s;
  s.start(scene, scene.params, scene.rules, frame);
  s.job().wait();
  ASSERT_TRUE(s.job().result().has_value()) << s.job().error();
  const SubstepSuggestion& got = s.job().result()->substeps;
  EXPECT_EQ(got.frame_dt, frame);
  for (const auto& [g, w] : {std::pair{&got.exact, &want.exact}, std::pair{&got.safe, &want.safe}}) {
    EXPECT_EQ(g->n, w->n);
    EXPECT_EQ(g->dt, frame / g->n);
    EXPECT_LT(g->dt, g->limit);
    EXPECT_GE(frame / (g->n - 1), g->limit);  // the fewest
    EXPECT_TRUE(g->ran);
    EXPECT_EQ(g->run.label, w->run.label);
    EXPECT_EQ(g->run.result.outcome, w->run.result.outcome);
    EXPECT_EQ(g->run.result.iterations, w->run.result.iterations);
    EXPECT_TRUE(g->run.verified());
    EXPECT_EQ(with_substeps(scene.params, *g).dt, g->dt);
  }
}

TEST(TunerSubsteps, CancelDropsTheComputation) {
  const SceneSpec scene = small_plane(8, 400);
  TunerSubsteps s;
  s.start(scene, scene.params, scene.rules, 2.0);
  EXPECT_TRUE(s.job().busy());
  s.job().cancel();
  EXPECT_FALSE(s.job().busy());
  EXPECT_TRUE(s.job().cancelled());
  s.job().wait();
  EXPECT_FALSE(s.job().result().has_value());
  EXPECT_TRUE(s.job().error().empty());
}

// Where one step per frame is not stable, SPEC 11's alternative comes with the counts: core's
// answer for dt* = F, and the scaled scene the apply button switches the live model to.
TEST(TunerSubsteps, OffersTheMassThatMakesOneStepPerFrameStable) {
  SceneSpec scene = small_plane(8, 400);
  for (int a : {3, 4})
    for (int b : {3, 4}) scene.model.mass_scale[static_cast<size_t>(a * 8 + b)] = 0.1;
  const double frame = 0.3;  // SPEC 11's plane (no corner fixed here)
  TunerSubsteps s;
  s.start(scene, scene.params, scene.rules, frame);
  s.job().wait();
  ASSERT_TRUE(s.job().result().has_value()) << s.job().error();
  const SubstepsResult& r = *s.job().result();
  ASSERT_GT(r.substeps.exact.n, 1);
  ASSERT_TRUE(r.mass.has_value());
  const SceneMassScaling want = scene_mass_scaling(scene, scene.params, scene.rules, frame);
  EXPECT_EQ(r.mass->result.kind, MassScalingCase::scaled);
  EXPECT_EQ(r.mass->result.scaled_count, want.result.scaled_count);
  EXPECT_EQ(r.mass->mass_after, want.mass_after);
  EXPECT_TRUE(r.mass->run.verified());
  const std::vector<float> shade = added_mass_shade(*r.mass);
  ASSERT_EQ(shade.size(), scene.model.rest.size());
  EXPECT_EQ(*std::max_element(shade.begin(), shade.end()), 1.0f);
  EXPECT_EQ(shade[0], 0.0f);
  // Apply: the live model takes the scaled masses and dt = F.
  Tuner t(scene);
  t.set_scene(r.mass->scene);
  EXPECT_EQ(t.session().model().mass, want.mass_after);
  EXPECT_EQ(t.params().dt, frame);
}

// A count that does not exist (limit unknown or over kMaxSubsteps) leaves dt as it is.
TEST(TunerSubsteps, ApplyingNoCountKeepsDt) {
  Params p;
  EXPECT_EQ(with_substeps(p, SubstepCount{}).dt, p.dt);
}

}  // namespace
}  // namespace dampbound::ui
