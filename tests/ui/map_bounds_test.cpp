// The stability map's boundary lines (ui/map_bounds.hpp): on each line the criterion it draws
// flips, on uniform and non-uniform scenes.
#include "ui/map_bounds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/io/scene_file.hpp"
#include "core/sweep/summary.hpp"
#include "dampbound/physics/bounds.hpp"
#include "tests/ui/ui_test_util.hpp"

namespace dampbound::ui {
namespace {

using ui_test::small_plane;

TEST(MapBounds, BoundLinesOfAUniformScene) {
  const SceneSpec scene = small_plane(10, 300);
  const MapBoundConstants k = map_bound_constants(scene);
  EXPECT_DOUBLE_EQ(k.lower, 1.0);
  EXPECT_DOUBLE_EQ(k.rate_ratio, 1.0);
  EXPECT_DOUBLE_EQ(k.lambda_unit, unit_stiffness_eigenvalue(scene));
  Params p = scene.params;  // m = kappa = 0.001
  MapView v;                // gamma against dt
  const auto lines =
      map_bound_lines(k, p, v, map_log_edges(p.dt, 1, 8), map_log_edges(0.002, 1, 8));
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
  const auto kl =
      map_bound_lines(k, p, kv, map_log_edges(p.kappa, 1, 8), map_log_edges(p.dt, 1, 8));
  ASSERT_EQ(kl.size(), 3u);  // the lower bound: a vertical line at kappa = gamma^2 / (4 m)
  for (double x : kl[0].x) EXPECT_NEAR(x, p.gamma * p.gamma / (4 * p.m), 1e-15);
  for (size_t i = 0; i < kl[1].x.size(); ++i)
    EXPECT_NEAR(
        kl[1].y[i] * kl[1].y[i] * k.lambda_unit * kl[1].x[i] / p.m + 2 * p.gamma / p.m * kl[1].y[i],
        4, 1e-9);
  for (size_t i = 0; i < kl[2].x.size(); ++i) {  // the safe dt at each kappa
    EXPECT_TRUE(safe_at_rest(k.safe, p.m, kl[2].x[i], p.gamma, kl[2].y[i] * (1 - 1e-9)));
    EXPECT_FALSE(safe_at_rest(k.safe, p.m, kl[2].x[i], p.gamma, kl[2].y[i] * (1 + 1e-9)));
  }
}

TEST(MapBounds, BoundLinesOfANonUniformSceneUseTheWorstNode) {
  const SceneSpec scene =
      load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/stiff-region.toml");
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

}  // namespace
}  // namespace dampbound::ui
