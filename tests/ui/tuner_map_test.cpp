// The tuner's stability map without a window (ui/tuner_map.hpp): the worker's passes and when
// it restarts.
#include "ui/tuner_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/io/scene_file.hpp"
#include "dampbound/physics/bounds.hpp"
#include "ui/tuner.hpp"
#include "tests/ui/ui_test_util.hpp"

namespace dampbound::ui {
namespace {

using ui_test::small_plane;

TEST(TunerMap, WorkerPassesCoarseToFineAndFollowsTheCentre) {
  const auto shared = std::make_shared<const SceneSpec>(small_plane(10, 300));
  const SceneSpec& scene = *shared;
  TunerMap map;
  MapView view;
  view.finest = 16;
  Params p = scene.params;
  map.follow(shared, 1, p, scene.rules, view);
  map.wait();
  ASSERT_EQ(map.unsupported(), "");
  auto r = map.result();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->pass, 2);  // 8 x 8, then 16 x 16
  EXPECT_TRUE(r->finest);
  ASSERT_EQ(r->cells.size(), 256u);
  // The finished pass holds what the kernel gives for its grid.
  const auto again = run_map_trials(
      scene, p, scene.rules,
      map_trials(p, view.x, map_cell_centres(r->x_edges), view.y, map_cell_centres(r->y_edges)));
  for (size_t k = 0; k < again.size(); ++k) {
    EXPECT_EQ(again[k].outcome, r->cells[k].outcome);
    EXPECT_EQ(again[k].iterations, r->cells[k].iterations);
  }
  EXPECT_EQ(map.starts(), 1);
  map.follow(shared, 1, p, scene.rules, view);  // nothing changed
  p.gamma *= 1.5;                                // within the middle half of the window
  map.follow(shared, 1, p, scene.rules, view);
  EXPECT_EQ(map.starts(), 1);
  p.gamma *= 10;  // out of it: the window moves
  map.follow(shared, 1, p, scene.rules, view);
  EXPECT_EQ(map.starts(), 2);
  p.m *= 1.01;  // off the axes: every cell changes
  map.follow(shared, 1, p, scene.rules, view);
  EXPECT_EQ(map.starts(), 3);
  map.wait();
  ASSERT_TRUE(map.result());
  Params q = p;  // another scene (key 2), centred elsewhere: nothing of the last one shows
  q.m *= 1.5;
  map.follow(shared, 2, q, scene.rules, view);
  EXPECT_EQ(map.starts(), 4);
  EXPECT_TRUE(!map.result() || map.result()->base.m == q.m) << "the last scene's map is on show";
  map.stop();
}

TEST(TunerMap, SceneTheKernelCannotRunSaysWhy) {
  SceneSpec scene = small_plane(10, 300);
  scene.cuts.push_back({5, {0, 0}, {1, 1}});
  TunerMap map;
  map.follow(std::make_shared<const SceneSpec>(scene), 1, scene.params, scene.rules, MapView{});
  EXPECT_NE(map.unsupported(), "");
  EXPECT_FALSE(map.result());
}

// The parameters panel's lower-bound line on a non-uniform mesh: the worst node speaks.
TEST(TunerMap, LowerBoundCheckNamesTheWorstNode) {
  SceneSpec scene = load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/stiff-region.toml");
  Tuner t(scene);
  Params p = t.params();
  p.gamma = 0.005;
  ASSERT_TRUE(t.set_params(p));
  const LowerBoundCheck c = check_lower_bound(t.session().model());
  EXPECT_FALSE(c.uniform);
  EXPECT_EQ(c.below, 169);  // the 13 x 13 stiff square
  EXPECT_EQ(c.nodes, 1296);
  EXPECT_NEAR(c.ratio, 0.005 / (2 * std::sqrt(0.004 * 0.01)), 1e-12);
  EXPECT_TRUE(t.session().model().spec().mass_scale[static_cast<size_t>(c.worst)] == 4.0);
  Tuner u(small_plane(10, 300));
  const LowerBoundCheck d = check_lower_bound(u.session().model());
  EXPECT_TRUE(d.uniform);
  EXPECT_EQ(d.below, 0);
  EXPECT_NEAR(d.ratio, 1.0, 1e-12);  // the default gamma is the lower bound
}

}  // namespace
}  // namespace dampbound::ui
