// The tuner's stability map without a window (ui/tuner_map.hpp): its cells against `sweep` on
// the same grid, the worker's passes and when it restarts, and the boundary lines.
#include "ui/tuner_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "core/bounds.hpp"
#include "core/sweep/runner.hpp"
#include "core/sweep/summary.hpp"
#include "ui/tuner.hpp"
#include "core/io/scene_file.hpp"

namespace dampbound::ui {
namespace {

SceneSpec small_plane() {
  SceneSpec s = paper_plane_scene(10);
  s.name = "small-plane";
  s.rules.max_iterations = 300;
  return s;
}

std::uint64_t bits(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// The map's cells are the outcomes `dampbound sweep` finds for the same trials: the same
// grid of (dt, gamma) run once through the map and once through the sweep runner (its
// similarity classes, its kernel threads, its CSV rows).
TEST(TunerMap, CellsEqualSweepOnTheSameGrid) {
  const SceneSpec scene = small_plane();
  const std::vector<double> dts = {0.05, 0.2, 0.5, 0.9}, gammas = {0, 0.0005, 0.002, 0.01};
  Params base = scene.params;
  base.m = base.kappa = 0.001;
  const std::vector<TrialResult> cells =
      run_map_trials(scene, base, scene.rules, map_trials(base, MapParam::dt, dts, MapParam::gamma, gammas));
  ASSERT_EQ(cells.size(), 16u);

  SweepRequest rq;
  rq.scene = scene;
  rq.scene_text = "small-plane built in code";
  rq.spec.m = parse_axis("--m", "0.001", AxisDomain::positive);
  rq.spec.kappa = parse_axis("--kappa", "0.001", AxisDomain::positive);
  rq.spec.gamma = parse_axis("--gamma", "0,0.0005,0.002,0.01", AxisDomain::non_negative);
  rq.spec.dt = parse_axis("--dt", "0.05,0.2,0.5,0.9", AxisDomain::positive);
  rq.spec.factor = parse_axis("--factor", "1", AxisDomain::non_negative);
  rq.spec.policy = DampingPolicy::fixed;
  rq.spec.rules = scene.rules;
  const auto dir = std::filesystem::temp_directory_path() / "dampbound_tuner_map_sweep";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  rq.output = (dir / "sweep.csv").string();
  rq.threads = 2;
  const SweepReport rep = run_sweep(rq);
  ASSERT_EQ(rep.rows.size(), 16u);
  std::map<std::pair<double, double>, const SweepRow*> by;
  for (const SweepRow& r : rep.rows) by[{r.dt, r.gamma}] = &r;
  std::set<Outcome> seen;
  for (size_t iy = 0; iy < gammas.size(); ++iy)
    for (size_t ix = 0; ix < dts.size(); ++ix) {
      SCOPED_TRACE("dt " + std::to_string(dts[ix]) + ", gamma " + std::to_string(gammas[iy]));
      const TrialResult& c = cells[iy * dts.size() + ix];
      const auto it = by.find({dts[ix], gammas[iy]});
      ASSERT_NE(it, by.end());
      EXPECT_EQ(c.outcome, it->second->outcome);
      EXPECT_EQ(c.iterations, it->second->iterations);
      EXPECT_EQ(bits(c.max_displacement), bits(it->second->max_displacement));
      seen.insert(c.outcome);
    }
  // The grid crosses the outcomes, so the comparison means something.
  EXPECT_GE(seen.size(), 2u);
  EXPECT_TRUE(seen.count(Outcome::diverged));
}

TEST(TunerMap, LogGridAroundTheCentre) {
  const auto e = map_log_edges(0.01, 1.0, 4);
  ASSERT_EQ(e.size(), 5u);
  EXPECT_NEAR(e.front(), 0.001, 1e-15);
  EXPECT_NEAR(e[2], 0.01, 1e-15);
  EXPECT_NEAR(e.back(), 0.1, 1e-14);
  const auto c = map_cell_centres(e);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_NEAR(c[0], std::sqrt(e[0] * e[1]), 1e-18);
  Params p = default_params();
  const auto trials = map_trials(p, MapParam::kappa, {1, 2}, MapParam::m, {3, 4, 5});
  ASSERT_EQ(trials.size(), 6u);
  EXPECT_EQ(trials[1].kappa, 2);  // x fastest
  EXPECT_EQ(trials[1].m, 3);
  EXPECT_EQ(trials[4].m, 5);
}

TEST(TunerMap, WorkerPassesCoarseToFineAndFollowsTheCentre) {
  const SceneSpec scene = small_plane();
  TunerMap map;
  MapView view;
  view.finest = 16;
  Params p = scene.params;
  map.follow(scene, 1, p, scene.rules, view);
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
  map.follow(scene, 1, p, scene.rules, view);  // nothing changed
  p.gamma *= 1.5;                                // within the middle half of the window
  map.follow(scene, 1, p, scene.rules, view);
  EXPECT_EQ(map.starts(), 1);
  p.gamma *= 10;  // out of it: the window moves
  map.follow(scene, 1, p, scene.rules, view);
  EXPECT_EQ(map.starts(), 2);
  p.m *= 1.01;  // off the axes: every cell changes
  map.follow(scene, 1, p, scene.rules, view);
  EXPECT_EQ(map.starts(), 3);
  map.follow(scene, 2, p, scene.rules, view);  // another scene
  EXPECT_EQ(map.starts(), 4);
  map.stop();
}

TEST(TunerMap, SceneTheKernelCannotRunSaysWhy) {
  SceneSpec scene = small_plane();
  scene.cuts.push_back({5, {0, 0}, {1, 1}});
  TunerMap map;
  map.follow(scene, 1, scene.params, scene.rules, MapView{});
  EXPECT_NE(map.unsupported(), "");
  EXPECT_FALSE(map.result());
}

TEST(TunerMap, BoundLinesOfAUniformScene) {
  const SceneSpec scene = small_plane();
  const MapBoundConstants k = map_bound_constants(scene);
  EXPECT_DOUBLE_EQ(k.lower, 1.0);
  EXPECT_DOUBLE_EQ(k.rate_ratio, 1.0);
  EXPECT_DOUBLE_EQ(k.lambda_unit, unit_stiffness_eigenvalue(scene));
  Params p = scene.params;  // m = kappa = 0.001
  MapView v;                // gamma against dt
  const auto lines = map_bound_lines(k, p, v, map_log_edges(p.dt, 1, 8), map_log_edges(0.002, 1, 8));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].kind, MapLineKind::paper);
  for (double y : lines[0].y) EXPECT_DOUBLE_EQ(y, lower_bound(p.m, p.kappa));
  EXPECT_EQ(lines[1].kind, MapLineKind::exact_linear);
  ASSERT_GT(lines[1].x.size(), 10u);
  for (size_t i = 0; i < lines[1].x.size(); ++i) {
    // On the line the step is at SPEC 7's limit: stable just below it, unstable just above.
    const double dt = lines[1].x[i], g = lines[1].y[i];
    EXPECT_FALSE(linearly_unstable(p.m, p.kappa, g * (1 - 1e-9), dt, k.lambda_unit));
    EXPECT_TRUE(linearly_unstable(p.m, p.kappa, g * (1 + 1e-9), dt, k.lambda_unit));
  }
  // SPEC 9's safe bound: on its line the safe check at rest flips, and it lies inside the exact
  // limit (sufficient, never looser).
  EXPECT_EQ(lines[2].kind, MapLineKind::safe);
  ASSERT_GT(lines[2].x.size(), 10u);
  for (size_t i = 0; i < lines[2].x.size(); ++i) {
    const double dt = lines[2].x[i], g = lines[2].y[i];
    EXPECT_TRUE(safe_at_rest(k.safe, p.m, p.kappa, g * (1 - 1e-9), dt));
    EXPECT_FALSE(safe_at_rest(k.safe, p.m, p.kappa, g * (1 + 1e-9), dt));
    EXPECT_FALSE(linearly_unstable(p.m, p.kappa, g, dt, k.lambda_unit));
  }
  // dt against kappa: the exact limit is solved for dt where kappa is the axis.
  MapView kv;
  kv.x = MapParam::kappa;
  kv.y = MapParam::dt;
  const auto kl = map_bound_lines(k, p, kv, map_log_edges(p.kappa, 1, 8), map_log_edges(p.dt, 1, 8));
  ASSERT_EQ(kl.size(), 3u);  // the lower bound: a vertical line at kappa = gamma^2 / (4 m)
  for (double x : kl[0].x) EXPECT_NEAR(x, p.gamma * p.gamma / (4 * p.m), 1e-15);
  for (size_t i = 0; i < kl[1].x.size(); ++i)
    EXPECT_NEAR(kl[1].y[i] * kl[1].y[i] * k.lambda_unit * kl[1].x[i] / p.m +
                    2 * p.gamma / p.m * kl[1].y[i],
                4, 1e-9);
  for (size_t i = 0; i < kl[2].x.size(); ++i) {  // the safe dt at each kappa
    EXPECT_TRUE(safe_at_rest(k.safe, p.m, kl[2].x[i], p.gamma, kl[2].y[i] * (1 - 1e-9)));
    EXPECT_FALSE(safe_at_rest(k.safe, p.m, kl[2].x[i], p.gamma, kl[2].y[i] * (1 + 1e-9)));
  }
}

TEST(TunerMap, BoundLinesOfANonUniformSceneUseTheWorstNode) {
  const SceneSpec scene = load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/stiff-region.toml");
  const MapBoundConstants k = map_bound_constants(scene);
  EXPECT_NEAR(k.lower, std::sqrt(4.0 * 10.0), 1e-12);  // 4x heavier, 10x stiffer
  EXPECT_TRUE(std::isnan(k.rate_ratio));               // gamma/m differs: no exact line
  EXPECT_TRUE(std::isnan(k.lambda_unit));
  const auto lines = map_bound_lines(k, scene.params, MapView{}, map_log_edges(0.05, 1, 8),
                                     map_log_edges(0.02, 1, 8));
  ASSERT_EQ(lines.size(), 2u);  // the worst node's lower bound and the safe bound
  EXPECT_NEAR(lines[0].y[0], 2 * std::sqrt(40.0) * std::sqrt(0.001 * 0.001), 1e-15);
  EXPECT_EQ(lines[1].kind, MapLineKind::safe);
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
  EXPECT_TRUE(t.session().model().mass_scale[static_cast<size_t>(c.worst)] == 4.0);
  Tuner u(small_plane());
  const LowerBoundCheck d = check_lower_bound(u.session().model());
  EXPECT_TRUE(d.uniform);
  EXPECT_EQ(d.below, 0);
  EXPECT_NEAR(d.ratio, 1.0, 1e-12);  // the default gamma is the lower bound
}

}  // namespace
}  // namespace dampbound::ui
