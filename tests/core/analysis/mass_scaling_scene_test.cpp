// SPEC 11 on scenes: the report (the nodes given the most mass and why), the check by
// running, and the scaled scene written as TOML and read back exactly.
#include "core/analysis/mass_scaling_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/io/scene_file.hpp"
#include "core/io/scene_write.hpp"
#include "core/physics/damping_ratio.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

/// SPEC 11's example as a scene: paper_plane_scene(8) (node (4, 4) pulled 5 cm), node 0
/// fixed, the 2 x 2 patch (3..4, 3..4) at mass_scale 0.1, nodal gamma 0.002.
SceneSpec spec_scene() {
  SceneSpec s = paper_plane_scene(8);
  s.model.fixed[0] = 1;
  for (int a : {3, 4})
    for (int b : {3, 4}) s.model.mass_scale[static_cast<size_t>(a * 8 + b)] = 0.1;
  s.params.m = s.params.kappa = 0.001;
  s.params.gamma = 0.002;
  return s;
}

TEST(MassScalingScene, SpecPlaneReportsTheLightPatchAndItsRunSettles) {
  const SceneSpec scene = spec_scene();
  const SceneMassScaling s = scene_mass_scaling(scene, scene.params, scene.rules, 0.3);
  ASSERT_EQ(s.result.kind, MassScalingCase::scaled);
  ASSERT_EQ(s.top.size(), 4u);
  for (const ScaledNode& n : s.top) {
    const int a = n.node / 8, b = n.node % 8;
    EXPECT_TRUE(a >= 3 && a <= 4 && b >= 3 && b <= 4) << n.node;
    EXPECT_NEAR(n.before, 0.0001, 1e-18);
    EXPECT_EQ(n.factor, n.after / n.before);
    EXPECT_NE(n.cause.find("mass 10x below"), std::string::npos) << n.cause;
  }
  // Every answer mass is params.m x its scale exactly, at least m(s*), and an ulp at most above.
  int b = 0;
  for (size_t i = 0; i < s.mass_after.size(); ++i) {
    EXPECT_EQ(s.mass_after[i], s.params.m * s.mass_scale[i]);
    if (scene.model.fixed[i]) continue;
    const double want = s.result.mass[static_cast<size_t>(b++)];
    EXPECT_GE(s.mass_after[i], want);
    EXPECT_LE(s.mass_after[i], std::nextafter(want, 1.0));
  }
  // Eq. 5 grows as sqrt(factor). The plane's lowest frequency is its anchors' floor,
  // sqrt(kappa_a / m) at the nodes that keep their mass: unchanged (tissue-slivers' falls,
  // tests/cli/mass_scale.sh).
  EXPECT_NEAR(s.lower_bound_change, 100 * (std::sqrt(s.top.front().factor) - 1), 1e-9);
  EXPECT_EQ(s.frequency_change, 0);
  EXPECT_NEAR(s.frequency_before, 1, 1e-9);
  // SPEC 11: "a run at 0.3 s returns" (settled rule, the scene's protocol).
  ASSERT_TRUE(s.ran);
  EXPECT_EQ(s.run.params.dt, 0.3);
  EXPECT_TRUE(s.run.verified()) << static_cast<int>(s.run.result.outcome);
  // With the masses as given the same run diverges.
  const VerifiedRun before = verify_run(scene, s.params, scene.rules, "");
  EXPECT_EQ(before.result.outcome, Outcome::diverged);
}

/// Writes the scaled scene and reads it back.
SceneSpec round_trip(const SceneSpec& s) {
  return parse_scene(scene_toml(s, "/tmp/scaled.toml"), "/tmp/scaled.toml");
}

void expect_same(const SceneSpec& a, const SceneSpec& b) {
  EXPECT_TRUE(same_topology(a.model, b.model));
  EXPECT_EQ(a.model.mass_scale, b.model.mass_scale);
  EXPECT_EQ(a.params.dt, b.params.dt);
  EXPECT_EQ(a.params.gamma, b.params.gamma);
  EXPECT_EQ(a.params.kd, b.params.kd);
  EXPECT_EQ(a.params.rayleigh_mass, b.params.rayleigh_mass);
  EXPECT_EQ(a.params.rayleigh_stiffness, b.params.rayleigh_stiffness);
  const Model ma = compile_model(a.model, a.params), mb = compile_model(b.model, b.params);
  EXPECT_EQ(ma.mass, mb.mass);
  EXPECT_EQ(ma.gamma, mb.gamma);
  EXPECT_EQ(ma.spring_kd, mb.spring_kd);
  EXPECT_EQ(ma.anchor_kd, mb.anchor_kd);
}

TEST(MassScalingScene, ScaledSceneReadsBackToTheSameMassesAndIsStableAtTheTarget) {
  const SceneSpec scene = spec_scene();
  const SceneMassScaling s = scene_mass_scaling(scene, scene.params, scene.rules, 0.3);
  const SceneSpec back = round_trip(s.scene);
  expect_same(s.scene, back);
  EXPECT_TRUE(back.expectations.empty());
  SceneMassScalingOptions quiet;
  quiet.verify = false;
  const SceneMassScaling again = scene_mass_scaling(back, back.params, back.rules, 0.3, quiet);
  EXPECT_EQ(again.result.kind, MassScalingCase::nothing_to_add);
  EXPECT_GE(again.result.dt_limit_before, 0.3 / 0.9);
}

TEST(MassScalingScene, DashpotsRayleighAndAnchorScalesRoundTrip) {
  SceneSpec scene = spec_scene();
  scene.params.kd = 0.0002;
  scene.params.rayleigh_mass = 0.3;
  scene.params.rayleigh_stiffness = 0.01;
  scene.model.anchor_kd_scale.assign(scene.model.rest.size(), 1.0);
  scene.model.anchor_kd_scale[5] = 0.25;
  scene.model.springs[3].kd_scale = 3;
  SceneMassScalingOptions o;
  o.verify = false;
  o.max_added = 1;
  const SceneMassScaling s = scene_mass_scaling(scene, scene.params, scene.rules, 0.15, o);
  ASSERT_EQ(s.result.kind, MassScalingCase::scaled);
  const SceneSpec back = round_trip(s.scene);
  expect_same(s.scene, back);
  ASSERT_EQ(back.model.springs.size(), s.scene.model.springs.size());
  EXPECT_EQ(back.model.springs[3].kd_scale, 3);
}

TEST(MassScalingScene, ZetaIsResolvedBeforeTheMassesChange) {
  SceneSpec scene = spec_scene();
  scene.params.zeta = 0.5;
  SceneMassScalingOptions o;
  o.verify = false;
  const SceneMassScaling s = scene_mass_scaling(scene, scene.params, scene.rules, 0.3, o);
  EXPECT_FALSE(s.scene.params.zeta.has_value());
  // gamma_i = zeta 2 sqrt(m_i kappa_i) with the masses as given, kept in the scaled scene.
  const Model given = [&] {
    SceneSpec c = scene;
    Params p = c.params;
    resolve_zeta(c.model, p);
    return compile_model(c.model, p);
  }();
  const Model scaled = compile_model(s.scene.model, s.scene.params);
  EXPECT_EQ(given.gamma, scaled.gamma);
}

}  // namespace
}  // namespace dampbound
