// A scene's [mesh] table and its [[mesh_region]]s (core/io/detail/scene_mesh.hpp): the shipped
// tissue block, region scales, and the errors naming the scene's line.
// Tested through load_scene: the private header pulls in toml++.
#include "core/io/scene_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>

#include "core/io/mesh_file.hpp"
#include "core/io/scene_text.hpp"
#include "dampbound/physics/error.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

TEST(SceneMesh, TissueBlockScene) {
  const SceneSpec s = load_scene(test::source_path("scenes/tissue-block.toml"));
  EXPECT_EQ(s.model.node_count(), 27 * 11 * 21);
  EXPECT_EQ(std::count(s.model.fixed.begin(), s.model.fixed.end(), 1), 27 * 21);  // the base
  EXPECT_EQ(s.perturbations.size(), 9u);  // the probe's 3 x 3 patch
  EXPECT_EQ(s.model.anchor_count(), 0);
  // Geometric masses: not uniform (a corner holds fewer tetrahedra than an inner node).
  const auto [lo, hi] = std::minmax_element(s.model.mass_scale.begin(), s.model.mass_scale.end());
  EXPECT_GT(*hi / *lo, 5.0);
  // Its [[mesh_region]] tables are kept by name with their nodes (suggest --kappa-max).
  ASSERT_EQ(s.regions.size(), 2u);
  EXPECT_EQ(s.regions[0].label, "base");
  EXPECT_EQ(s.regions[0].nodes.size(), 27u * 21u);
  EXPECT_EQ(s.regions[1].label, "probe");
  EXPECT_EQ(s.regions[1].nodes.size(), 9u);
  EXPECT_TRUE(std::is_sorted(s.regions[0].nodes.begin(), s.regions[0].nodes.end()));
}

TEST(SceneMesh, BoxRegionsAreKeptWithTheirLine) {
  const SceneSpec s = load_scene(test::source_path("scenes/stiff-region.toml"));
  ASSERT_EQ(s.regions.size(), 1u);
  EXPECT_EQ(s.regions[0].label, "region 1 (line 20)");
  EXPECT_EQ(s.regions[0].nodes.size(), 13u * 13u);
  for (int i : s.regions[0].nodes) EXPECT_EQ(s.model.mass_scale[static_cast<size_t>(i)], 4.0);
}

TEST(SceneMesh, MeshRegionErrorsNameTheSceneLine) {
  // The scene in the temporary folder names the corpus mesh by its absolute path, which
  // only --allow-any-path permits (docs/hardening.md).
  struct AnyPath {
    AnyPath() { set_scene_paths_unrestricted(true); }
    ~AnyPath() { set_scene_paths_unrestricted(false); }
  } any_path;
  const std::string dir = ::testing::TempDir();
  const std::string scene = dir + "mesh_region.toml";
  const std::string mesh = test::source_path("tests/fuzz/corpus/msh/block-41.msh");
  auto scene_error = [&](const std::string& toml) {
    std::ofstream(scene) << "[mesh]\nfile = \"" << mesh << "\"\n" << toml;
    return test::input_error([&] { load_scene(scene); });
  };
  EXPECT_EQ(scene_error("[[mesh_region]]\nname = \"probe\"\nfixed = true\n"), "");
  EXPECT_EQ(scene_error("[[mesh_region]]\nname = \"bone\"\n"),
            scene + ":4: the mesh has no region named 'bone' (it has base, probe, tissue)");
  EXPECT_EQ(scene_error("[[mesh_region]]\ntag = 9\n"),
            scene + ":4: no element of the mesh has region tag 9 (it has 1, 2, 3)");
  EXPECT_EQ(scene_error("[[mesh_region]]\ntag = 2\nname = \"base\"\n"),
            scene + ":3: [[mesh_region]] needs one of tag or name");
  EXPECT_EQ(scene_error("format = \"stl\"\n"),
            scene + ":3: format must be one of obj, msh, tetgen, vtk");
  EXPECT_EQ(scene_error("[[mesh_region]]\nname = \"base\"\nfixed = true\n"
                        "[[mesh_region]]\nname = \"base\"\ndisplacement = [0, 1, 0]\n"),
            scene + ":8: the region's node 0 is fixed");
  // Multiplied scales: mass_scale 2 on the probe doubles its nodes' lumped masses.
  std::ofstream(scene) << "[mesh]\nfile = \"" << mesh << "\"\ndensity = 1.0\n"
                       << "[[mesh_region]]\nname = \"probe\"\nmass_scale = 2.0\n";
  const SceneSpec s = load_scene(scene);
  MeshSprings how;
  how.density = 1.0;
  const ModelSpec plain = model_from_mesh(read_mesh_file(mesh), how);
  const auto probe = region_nodes(read_mesh_file(mesh)).at(3);
  for (int i : probe)
    EXPECT_DOUBLE_EQ(s.model.mass_scale[size_t(i)], 2 * plain.mass_scale[size_t(i)]);
}

}  // namespace
}  // namespace dampbound
