// The stability map's grid (ui/map_grid.hpp): the log window, the trials of its cells, and
// the cells against `sweep` on the same grid.
#include "ui/map_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "core/sweep/runner.hpp"
#include "tests/ui/ui_test_util.hpp"

namespace dampbound::ui {
namespace {

using ui_test::small_plane;

std::uint64_t bits(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// The map's cells are the outcomes `dampbound sweep` finds for the same trials: the same
// grid of (dt, gamma) run once through the map and once through the sweep runner (its
// similarity classes, its kernel threads, its CSV rows).
TEST(MapGrid, CellsEqualSweepOnTheSameGrid) {
  const SceneSpec scene = small_plane(10, 300);
  const std::vector<double> dts = {0.05, 0.2, 0.5, 0.9}, gammas = {0, 0.0005, 0.002, 0.01};
  Params base = scene.params;
  base.m = base.kappa = 0.001;
  const std::vector<TrialResult> cells = run_map_trials(
      scene, base, scene.rules, map_trials(base, MapParam::dt, dts, MapParam::gamma, gammas));
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

TEST(MapGrid, LogGridAroundTheCentre) {
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

TEST(MapGrid, ParamsByAxis) {
  Params p = default_params();
  for (MapParam a : {MapParam::m, MapParam::kappa, MapParam::gamma, MapParam::dt}) {
    set_param(p, a, 0.25 + static_cast<int>(a));
    EXPECT_EQ(get_param(p, a), 0.25 + static_cast<int>(a)) << to_string(a);
  }
  EXPECT_EQ(p.m, 0.25);
  EXPECT_EQ(p.dt, 3.25);
  EXPECT_EQ(map_axis_label(MapParam::gamma), "gamma (mass unit/s)");
}

}  // namespace
}  // namespace dampbound::ui
