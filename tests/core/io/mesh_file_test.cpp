// Mesh files by name (core/io/mesh_file.hpp): the format from the extension, and the same
// block in every format giving the same model.
#include "core/io/mesh_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "dampbound/physics/error.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

/// The small block of scripts/make-tissue-mesh.py --small: 4 x 3 x 4 nodes 0.5 cm apart,
/// 3 x 2 x 3 cubes of 6 tetrahedra; base and probe triangles.
CellMesh small_block(const std::string& file) {
  return read_mesh_file(test::source_path("tests/fuzz/corpus/" + file));
}

std::set<std::pair<int, int>> spring_set(const ModelSpec& m) {
  std::set<std::pair<int, int>> out;
  for (const Spring& s : m.springs) out.insert({std::min(s.i, s.j), std::max(s.i, s.j)});
  return out;
}

TEST(MeshFile, FormatFromTheExtensionOrTheName) {
  EXPECT_EQ(mesh_format("a/b.obj"), "obj");
  EXPECT_EQ(mesh_format("b.msh"), "msh");
  EXPECT_EQ(mesh_format("b.node"), "tetgen");
  EXPECT_EQ(mesh_format("b.ele"), "tetgen");
  EXPECT_EQ(mesh_format("b.vtk"), "vtk");
  EXPECT_EQ(mesh_format("b.stl"), std::nullopt);
  EXPECT_EQ(mesh_format("b.stl", "msh"), "msh");
  EXPECT_EQ(mesh_format("B.MSH"), "msh");
  EXPECT_EQ(mesh_format("dir.v2/mesh"), std::nullopt);  // a dot in a folder is no extension
  try {
    read_mesh_file("m.stl");
    ADD_FAILURE() << "read an .stl";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "m.stl: unknown mesh format (use .obj, .msh, .node/.ele or .vtk, or set "
              "format = \"obj\", \"msh\", \"tetgen\" or \"vtk\")");
  }
}

TEST(MeshFile, EveryFormatGivesTheSameBlock) {
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

}  // namespace
}  // namespace dampbound
