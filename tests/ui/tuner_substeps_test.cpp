// The Suggest tab's substeps per frame (ui/tuner_substeps.hpp): the counts of core's
// suggest_substeps, each verified on the worker, Cancel, and the apply button's dt.
#include "ui/tuner_substeps.hpp"

#include <gtest/gtest.h>

#include "core/scene.hpp"

namespace dampbound::ui {
namespace {

SceneSpec small_plane() {
  SceneSpec s = paper_plane_scene(8);
  s.rules.max_iterations = 400;
  return s;
}

// A frame of 2 s on the paper plane (exact dt limit about 0.5 s at gamma 0.002) needs
// several substeps: the worker gives core's counts and a settled run for each.
TEST(TunerSubsteps, GivesCoresCountsEachVerifiedByARun) {
  const SceneSpec scene = small_plane();
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
  const SceneSpec scene = small_plane();
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

// A count that does not exist (limit unknown or over kMaxSubsteps) leaves dt as it is.
TEST(TunerSubsteps, ApplyingNoCountKeepsDt) {
  Params p;
  EXPECT_EQ(with_substeps(p, SubstepCount{}).dt, p.dt);
}

}  // namespace
}  // namespace dampbound::ui
