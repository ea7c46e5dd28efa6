// Gmsh MSH files (core/io/mesh_msh.hpp): what a small file reads as, and the bad-input cases
// naming the line or the byte.
#include "core/io/mesh_msh.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "core/io/files.hpp"
#include "dampbound/physics/error.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

std::string msh_error(const std::string& text) {
  return test::input_error([&] { parse_msh(text.data(), text.size(), "m.msh"); });
}

const std::string kHead =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n"
    "3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n1\n";

TEST(MeshMsh, OneTetrahedronWithItsPhysicalGroup) {
  const std::string text =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 7 \"tissue\"\n"
      "$EndPhysicalNames\n$Nodes\n4\n1 0 0 0\n2 2 0 0\n3 0 3 0\n4 0 0 4\n$EndNodes\n"
      "$Elements\n1\n1 4 2 7 1 1 2 3 4\n$EndElements\n";
  const CellMesh m = parse_msh(text.data(), text.size(), "t.msh");
  ASSERT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.vertices[3], Vec3(0, 0, 4));
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].shape, CellShape::tetra);
  EXPECT_EQ(m.cells[0].corners, (std::vector<int>{0, 1, 2, 3}));  // tags 1..4 -> indices 0..3
  EXPECT_EQ(m.cells[0].region, 7);                                // the first tag (2.2)
  EXPECT_EQ(m.cells[0].where, 17);                                // its line
  EXPECT_EQ(m.region_names.at("tissue"), 7);
}

TEST(MeshMsh, BadInputNamesTheLine) {
  EXPECT_EQ(msh_error(kHead + "1 4 2 1 1 1 2 3 4\n$EndElements\n"), "");
  EXPECT_EQ(msh_error(kHead + "1 4 2 1 1 1 2 3 9\n$EndElements\n"),
            "m.msh:13: the element refers to node tag 9, which $Nodes does not define");
  EXPECT_EQ(msh_error(kHead + "1 4 2 1 1 1 3 2 4\n$EndElements\n"), "");  // either orientation
  EXPECT_EQ(msh_error(kHead + "1 5 2 1 1 1 2 3 4 1 2 3 4\n$EndElements\n"),
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
}

TEST(MeshMsh, CutBinaryFileFailsWithAByteOffset) {
  // A binary file cut anywhere in its data fails with a byte offset, never reads past the end.
  const std::string bin =
      read_file_text(test::source_path("tests/fuzz/corpus/msh/block-41b.msh"));
  for (size_t cut : {size_t(40), size_t(300), bin.size() / 2, bin.size() - 20}) {
    const std::string e = msh_error(bin.substr(0, cut));
    EXPECT_NE(e.find("m.msh: byte "), std::string::npos) << cut << ": " << e;
  }
}

}  // namespace
}  // namespace dampbound
