// The mesh readers (core/io/mesh_msh.hpp, mesh_tetgen.hpp, mesh_vtk.hpp) and the shared builder (core/io/mesh.hpp): the same
// block in every format gives the same model; geometric masses and stiffnesses; quads; the
// bad-input battery.
#include "core/io/scene_text.hpp"
#include "core/io/mesh_msh.hpp"
#include "core/io/mesh_tetgen.hpp"
#include "core/io/mesh_vtk.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "core/io/files.hpp"
#include "core/io/mesh_obj.hpp"
#include "core/scene.hpp"
#include "core/io/scene_file.hpp"
#include "core/io/mesh_file.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

const std::string kCorpus = "tests/fuzz/corpus/";

/// The small block of scripts/make-tissue-mesh.py --small: 4 x 3 x 4 nodes 0.5 cm apart,
/// 3 x 2 x 3 cubes of 6 tetrahedra; base and probe triangles.
CellMesh small_block(const std::string& file) {
  return read_mesh_file(test::source_path(kCorpus + file));
}

std::set<std::pair<int, int>> spring_set(const ModelSpec& m) {
  std::set<std::pair<int, int>> out;
  for (const Spring& s : m.springs) out.insert({std::min(s.i, s.j), std::max(s.i, s.j)});
  return out;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string msh_error(const std::string& text) {
  return error_of([&] { parse_msh(text.data(), text.size(), "m.msh"); });
}
std::string vtk_error(const std::string& text) {
  return error_of([&] { parse_vtk(text.data(), text.size(), "m.vtk"); });
}

TEST(MeshFormats, EveryFormatGivesTheSameBlock) {
  const char* files[] = {"msh/block-22.msh",  "msh/block-22b.msh", "msh/block-41.msh",
                         "msh/block-41b.msh", "tetgen/block.ele",  "vtk/block.vtk"};
  const CellMesh ref = small_block(files[0]);
  const ModelSpec ref_model = model_from_mesh(ref, MeshSprings{});
  ASSERT_EQ(ref.vertices.size(), 48u);
  // Edges of the Kuhn subdivision: 104 along the axes, 75 face diagonals, 18 body diagonals.
  EXPECT_EQ(ref_model.spring_count(), 104 + 75 + 18);
  EXPECT_EQ(std::count_if(ref.cells.begin(), ref.cells.end(),
                          [](const MeshCell& c) { return c.shape == CellShape::tetra; }),
            108);
  const auto ref_regions = region_nodes(ref);
  ASSERT_EQ(ref_regions.size(), 3u);
  EXPECT_EQ(ref_regions.at(1).size(), 48u);  // tissue: every node
  EXPECT_EQ(ref_regions.at(2).size(), 16u);  // base: the 4 x 4 nodes at y = 0
  EXPECT_EQ(ref_regions.at(3).size(), 9u);   // probe: 3 x 3 nodes on top
  for (const char* f : files) {
    SCOPED_TRACE(f);
    const CellMesh m = small_block(f);
    EXPECT_EQ(m.vertices, ref.vertices);
    EXPECT_EQ(spring_set(model_from_mesh(m, MeshSprings{})), spring_set(ref_model));
    EXPECT_EQ(region_nodes(m), ref_regions);
  }
  EXPECT_EQ(ref.region_names.at("probe"), 3);
  EXPECT_EQ(small_block("msh/block-41b.msh").region_names.at("base"), 2);
}

TEST(MeshFormats, LumpedMassesAndVolumeWeightedStiffness) {
  MeshSprings how;
  how.scale = 2.0;  // the block becomes 3 x 2 x 3 cm: 18 cm^3
  how.density = 0.5;
  how.young = 3.0;
  const ModelSpec m = model_from_mesh(small_block("msh/block-41.msh"), how);
  double mass = 0, moment = 0;
  for (double s : m.mass_scale) mass += s;
  EXPECT_NEAR(mass, 0.5 * 18.0, 1e-12);  // density x volume, split to the corners
  // sum_e k_e l_e^2 = E sum_e sum_{t holding e} V_t = 6 E V (six edges per tetrahedron).
  for (const Spring& s : m.springs) moment += s.kappa_scale * s.rest_length * s.rest_length;
  EXPECT_NEAR(moment, 6 * 3.0 * 18.0, 1e-9);
  // Node 0 at (0, 0, 0) starts every Kuhn path of its cube: in its 6 tetrahedra of 1/6 cm^3,
  // a quarter of each.
  EXPECT_NEAR(m.mass_scale[0], 0.5 * 1.0 / 4.0, 1e-12);
}

TEST(MeshFormats, QuadsGetShearAndFlexionSprings) {
  std::ostringstream obj;  // a 20 x 20 node sheet of quads
  for (int a = 0; a < 20; ++a)
    for (int b = 0; b < 20; ++b) obj << "v " << a << " 0 " << b << "\n";
  for (int a = 0; a < 19; ++a)
    for (int b = 0; b < 19; ++b)
      obj << "f " << a * 20 + b + 1 << " " << (a + 1) * 20 + b + 1 << " " << (a + 1) * 20 + b + 2
          << " " << a * 20 + b + 2 << "\n";
  const ObjMesh mesh = parse_obj(obj.str(), "sheet.obj");
  MeshSprings how;
  EXPECT_EQ(model_from_obj(mesh, how).spring_count(), 760 + 2 * 361);  // sides + diagonals
  how.bend = true;
  const ModelSpec bent = model_from_obj(mesh, how);
  // Flexion springs (a-1, b)-(a+1, b) and (a, b-1)-(a, b+1): 18 x 20 in each direction.
  EXPECT_EQ(bent.spring_count(), 760 + 722 + 720);
  const auto springs = spring_set(bent);
  EXPECT_TRUE(springs.count({0 * 20 + 5, 2 * 20 + 5}));
  EXPECT_TRUE(springs.count({7 * 20 + 0, 7 * 20 + 2}));
}

TEST(MeshFormats, BadInputNamesTheFileAndTheLineOrByte) {
  const std::string head =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n"
      "3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n1\n";
  EXPECT_EQ(msh_error(head + "1 4 2 1 1 1 2 3 4\n$EndElements\n"), "");
  EXPECT_EQ(msh_error(head + "1 4 2 1 1 1 2 3 9\n$EndElements\n"),
            "m.msh:13: the element refers to node tag 9, which $Nodes does not define");
  EXPECT_EQ(msh_error(head + "1 4 2 1 1 1 3 2 4\n$EndElements\n").substr(0, 33),
            "m.msh:13: inverted tetrahedron (s");
  EXPECT_EQ(msh_error(head + "1 5 2 1 1 1 2 3 4 1 2 3 4\n$EndElements\n"),
            "m.msh:13: unsupported element type 5 (hexahedron): only points, lines, triangles, "
            "quadrangles and tetrahedra are read");
  const std::string flat =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n"
      "3 0 1 0\n4 1 1 0\n$EndNodes\n$Elements\n1\n1 4 0 1 2 3 4\n$EndElements\n";
  EXPECT_EQ(msh_error(flat), "m.msh:13: degenerate tetrahedron (zero volume)");
  const std::string mixed =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n"
      "3 0 1 0\n4 0 0 1\n5 2 2 2\n$EndNodes\n$Elements\n2\n1 4 0 1 2 3 4\n"
      "2 2 0 1 2 5\n$EndElements\n";
  EXPECT_EQ(msh_error(mixed),
            "m.msh:15: mixed dimensions: this triangle has node 4, which no tetrahedron uses");
  EXPECT_EQ(msh_error("v 0 0 0\nf 1 2 3\n"),
            "m.msh:1: not a Gmsh MSH file (it does not start with $MeshFormat)");
  EXPECT_EQ(vtk_error("$MeshFormat\n"),
            "m.vtk:1: not a VTK legacy file (no '# vtk DataFile Version' header)");
  // A binary file cut anywhere in its data fails with a byte offset, never reads past the end.
  const std::string bin = read_file_text(test::source_path(kCorpus + "msh/block-41b.msh"));
  for (size_t cut : {size_t(40), size_t(300), bin.size() / 2, bin.size() - 20}) {
    const std::string e = msh_error(bin.substr(0, cut));
    EXPECT_NE(e.find("m.msh: byte "), std::string::npos) << cut << ": " << e;
  }
  const std::string node = "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
  EXPECT_EQ(error_of([&] { parse_tetgen(node, "b.node", "1 4 0\n1 1 2 3 5\n", "b.ele"); }),
            "b.ele:2: node number 5 does not exist (nodes are 1..4)");
  EXPECT_EQ(error_of([&] {
              parse_tetgen(node, "b.node", "2 4 0\n1 1 2 3 4\n2 1 3 2 4\n", "b.ele");
            }).substr(0, 30),
            "b.ele:3: inverted tetrahedron ");
  const std::string vtk =
      "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n"
      "POINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nCELLS 1 5\n4 0 1 2 3\n"
      "CELL_TYPES 1\n";
  EXPECT_EQ(vtk_error(vtk + "10\n"), "");
  EXPECT_EQ(vtk_error(vtk + "12\n"),
            "m.vtk:13: unsupported VTK cell type 12: only vertices (1), lines (3), triangles (5), "
            "polygons (7), quads (9) and tetrahedra (10) are read");
}

TEST(MeshFormats, TissueBlockScene) {
  const SceneSpec s = load_scene(test::source_path("scenes/tissue-block.toml"));
  EXPECT_EQ(s.model.node_count(), 27 * 11 * 21);
  EXPECT_EQ(std::count(s.model.fixed.begin(), s.model.fixed.end(), 1), 27 * 21);  // the base
  EXPECT_EQ(s.perturbations.size(), 9u);  // the probe's 3 x 3 patch
  EXPECT_EQ(s.model.anchor_count(), 0);
  // Geometric masses: not uniform (a corner holds fewer tetrahedra than an inner node).
  const auto [lo, hi] = std::minmax_element(s.model.mass_scale.begin(), s.model.mass_scale.end());
  EXPECT_GT(*hi / *lo, 5.0);
}

TEST(MeshFormats, MeshRegionErrorsNameTheSceneLine) {
  // The scene in the temporary folder names the corpus mesh by its absolute path, which
  // only --allow-any-path permits (docs/hardening.md).
  struct AnyPath {
    AnyPath() { set_scene_paths_unrestricted(true); }
    ~AnyPath() { set_scene_paths_unrestricted(false); }
  } any_path;
  const std::string dir = ::testing::TempDir();
  const std::string scene = dir + "mesh_region.toml";
  const std::string mesh = test::source_path(kCorpus + "msh/block-41.msh");
  auto scene_error = [&](const std::string& toml) {
    std::ofstream(scene) << "[mesh]\nfile = \"" << mesh << "\"\n" << toml;
    return error_of([&] { load_scene(scene); });
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
