// The Map tab with SPEC 10's damping: kd, rayleigh_mass and rayleigh_stiffness as axes, each
// cell run through Session (the batched kernel applies nodal damping only), and the nodal
// exact and safe lines left out where that damping is in the window.
#include <gtest/gtest.h>

#include "dampbound/run/scene.hpp"
#include "dampbound/run/session.hpp"
#include "ui/map_grid.hpp"
#include "ui/tuner_map.hpp"

namespace dampbound::ui {
namespace {

SceneSpec plane() {
  SceneSpec s = paper_plane_scene(6);
  s.rules.max_iterations = 300;
  s.rules.rule = StopRule::settled;
  s.params.kd = 0.002;
  return s;
}

TEST(MapDamping, EveryParameterIsAnAxis) {
  Params p;
  for (MapParam a : kMapParams) {
    set_param(p, a, 0.125 + static_cast<int>(a));
    EXPECT_EQ(get_param(p, a), 0.125 + static_cast<int>(a)) << to_string(a);
  }
  EXPECT_EQ(p.kd, 4.125);
  EXPECT_EQ(p.rayleigh_mass, 5.125);
  EXPECT_EQ(p.rayleigh_stiffness, 6.125);
  EXPECT_STREQ(to_string(MapParam::rayleigh_stiffness), "rayleigh_stiffness");
}

TEST(MapDamping, CellsWithDashpotsRunStepOneByOne) {
  const SceneSpec scene = plane();
  MapView view;
  view.x = MapParam::kd;
  view.y = MapParam::dt;
  EXPECT_TRUE(map_unsupported(scene, scene.params, view).empty());
  EXPECT_TRUE(map_runs_plain(scene.params, view));
  const std::vector<double> xs = map_cell_centres(map_log_edges(scene.params.kd, 1, 3));
  const std::vector<double> ys = map_cell_centres(map_log_edges(0.2, 0.5, 3));
  const std::vector<Params> cells = map_cell_params(scene.params, view.x, xs, view.y, ys);
  ASSERT_EQ(cells.size(), 9u);
  EXPECT_EQ(cells[5].kd, xs[2]);
  EXPECT_EQ(cells[5].dt, ys[1]);
  const std::vector<TrialResult> got = run_map_cells(scene, cells, scene.rules);
  ASSERT_EQ(got.size(), 9u);
  bool outcomes_differ = false;
  for (size_t k = 0; k < cells.size(); ++k) {
    Session s(scene, cells[k], scene.rules);
    const RunResult& want = s.run_to_end();
    EXPECT_EQ(got[k].outcome, want.outcome) << k;
    EXPECT_EQ(got[k].iterations, want.iterations) << k;
    EXPECT_EQ(got[k].max_displacement, want.max_displacement) << k;
    outcomes_differ |= got[k].outcome != got[0].outcome;
  }
  EXPECT_TRUE(outcomes_differ);  // the window spans the dashpots' dt limit
}

TEST(MapDamping, TheTunersMapTakesADampingAxis) {
  const SceneSpec scene = plane();
  MapView view;
  view.x = MapParam::dt;
  view.y = MapParam::kd;
  view.finest = 8;
  TunerMap map;
  map.follow(std::make_shared<const SceneSpec>(scene), 1, scene.params, scene.rules, view);
  map.wait();
  ASSERT_TRUE(map.unsupported().empty()) << map.unsupported();
  const auto r = map.result();
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->plain);
  EXPECT_EQ(r->cells.size(), 64u);
  for (const MapLine& l : r->lines) EXPECT_EQ(l.kind, MapLineKind::paper) << l.label;
  // Off (0) on a log axis: said, not drawn.
  Params off = scene.params;
  off.kd = 0;
  EXPECT_NE(map_unsupported(scene, off, view).find("kd"), std::string::npos);
  // Nodal damping only: the batched kernel, and the exact and safe lines again.
  view.y = MapParam::gamma;
  TunerMap nodal;
  nodal.follow(std::make_shared<const SceneSpec>(scene), 1, off, scene.rules, view);
  nodal.wait();
  ASSERT_TRUE(nodal.result());
  EXPECT_FALSE(nodal.result()->plain);
  EXPECT_GE(nodal.result()->lines.size(), 2u);
}

}  // namespace
}  // namespace dampbound::ui
