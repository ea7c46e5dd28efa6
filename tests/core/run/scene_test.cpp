// Scene builders (include/dampbound/run/scene.hpp): the built-in paper plane, models with region scales.
#include "dampbound/run/scene.hpp"

#include <gtest/gtest.h>

#include "core/io/scene_file.hpp"
#include "dampbound/physics/error.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

TEST(PaperPlane, BuiltInSceneIsTheFile) {
  const SceneSpec file = load_scene(test::source_path("scenes/paper-plane.toml"));
  const SceneSpec code = paper_plane_scene();
  EXPECT_EQ(code.name, file.name);
  EXPECT_EQ(code.description, file.description);
  ASSERT_EQ(code.model.node_count(), file.model.node_count());
  ASSERT_EQ(code.model.spring_count(), file.model.spring_count());
  for (int k = 0; k < code.model.spring_count(); ++k) {
    const Spring& a = code.model.springs[static_cast<size_t>(k)];
    const Spring& b = file.model.springs[static_cast<size_t>(k)];
    EXPECT_EQ(a.i, b.i);
    EXPECT_EQ(a.j, b.j);
    EXPECT_EQ(a.rest_length, b.rest_length);
    EXPECT_EQ(a.kappa_scale, b.kappa_scale);
  }
  EXPECT_EQ(code.model.rest, file.model.rest);
  EXPECT_EQ(code.model.anchor_scale, file.model.anchor_scale);
  EXPECT_EQ(code.model.mass_scale, file.model.mass_scale);
  EXPECT_EQ(code.model.gamma_scale, file.model.gamma_scale);
  EXPECT_EQ(code.model.fixed, file.model.fixed);
  EXPECT_EQ(code.watched, file.watched);
  ASSERT_EQ(code.perturbations.size(), file.perturbations.size());
  EXPECT_EQ(code.perturbations[0].node, file.perturbations[0].node);
  EXPECT_EQ(code.perturbations[0].displacement, file.perturbations[0].displacement);
  EXPECT_EQ(code.params.m, file.params.m);
  EXPECT_EQ(code.params.kappa, file.params.kappa);
  EXPECT_EQ(code.params.gamma, file.params.gamma);
  EXPECT_EQ(code.params.dt, file.params.dt);
  EXPECT_EQ(code.params.policy, file.params.policy);
  EXPECT_EQ(code.rules.max_iterations, file.rules.max_iterations);
  EXPECT_EQ(code.rules.restore_fraction, file.rules.restore_fraction);
  EXPECT_EQ(code.rules.diverge_factor, file.rules.diverge_factor);
  EXPECT_EQ(code.rules.reference, file.rules.reference);
  // A small one: the centre node of a 10 x 10 grid.
  const SceneSpec small = paper_plane_scene(10);
  EXPECT_EQ(small.model.node_count(), 100);
  EXPECT_EQ(small.watched, 55);
}

TEST(PaperPlane, UniformLowerBound) {
  const SceneSpec s = load_scene(test::source_path("scenes/paper-plane.toml"));
  Params p;
  p.m = 0.005, p.kappa = 0.1;
  const Model m = compile_model(s.model, p);
  for (double lo : m.lower_bound) EXPECT_DOUBLE_EQ(lo, 2 * std::sqrt(0.005 * 0.1));
}

TEST(NonUniform, RegionScalesAndMaxIncidentStiffness) {
  const SceneSpec s = parse_scene(R"(
[grid]
nx = 3
nz = 3
spacing = 1.0
[[region]]
min = [1.5, -1, -1]
max = [3, 1, 3]
mass_scale = 2
kappa_scale = 10
force = [0, -0.5, 0.25]
)",
                                  "region.toml");
  Params p;
  p.m = 1, p.kappa = 1;
  const Model m = compile_model(s.model, p);
  // Nodes with a = 2 are inside: mass 2, and springs between two of them are 10x stiffer.
  EXPECT_EQ(m.mass[2 * 3 + 1], 2.0);
  EXPECT_EQ(m.mass[1 * 3 + 1], 1.0);
  EXPECT_EQ(m.node_kappa[2 * 3 + 1], 10.0);
  EXPECT_EQ(m.node_kappa[1 * 3 + 1], 1.0);  // only its springs into the region are... 1x
  EXPECT_DOUBLE_EQ(m.lower_bound[2 * 3 + 1], 2 * std::sqrt(2.0 * 10.0));
  EXPECT_EQ(m.spec().external_force[2 * 3 + 1], Vec3(0, -0.5, 0.25));  // a load on the nodes inside
  EXPECT_EQ(m.spec().external_force[1 * 3 + 1], Vec3::Zero());
}

}  // namespace
}  // namespace dampbound
