// SPEC 9's bound node by node (core/physics/safe_bound_nodes.hpp), and SPEC 10's generalised rows where
// the model has dashpot or Rayleigh damping.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/physics/safe_bound.hpp"
#include "core/physics/safe_bound_nodes.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {
namespace {

TEST(SafeBoundNodes, NodalRowsAreSpec9sFormulas) {
  const SceneSpec scene = paper_plane_scene(6);
  const Model model = compile_model(scene.model, scene.params);
  std::vector<double> dts, gammas, R;
  safe_bounds_per_node(model, model.spec().rest, 0.05, dts, gammas);
  safe_row_sums(model, model.spec().rest, R);
  for (size_t i = 0; i < dts.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    EXPECT_EQ(dts[i], safe_dt(model.mass[i], model.gamma[i], R[i]));
    EXPECT_EQ(gammas[i], safe_gamma(model.mass[i], 0.05, R[i]));
  }
}

TEST(SafeBoundNodes, DashpotsUseTheGeneralisedRows) {
  const SceneSpec scene = paper_plane_scene(6);
  Params p = scene.params;
  p.kd = 0.002;
  const Model model = compile_model(scene.model, p);
  std::vector<double> dts, gammas;
  safe_bounds_per_node(model, model.spec().rest, 0.05, dts, gammas);
  const DampedSafeRows rows(model, model.spec().rest);
  double smallest = 1e300;
  for (size_t i = 0; i < dts.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    EXPECT_EQ(dts[i], rows.dt_safe(static_cast<int>(i), model.gamma[i]));
    EXPECT_EQ(gammas[i], rows.gamma_safe(static_cast<int>(i), 0.05));
    smallest = std::min(smallest, dts[i]);
  }
  // Dashpots shorten the safe step (the nodal rows would say 0.48 s on this plane).
  EXPECT_LT(smallest, 0.2);
}

}  // namespace
}  // namespace dampbound
