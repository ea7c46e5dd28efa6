// TetGen .node/.ele/.face files (core/io/mesh_tetgen.hpp): numbering from the first node,
// region attributes, face markers, and the bad-input cases naming the line.
#include "core/io/mesh_tetgen.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "dampbound/physics/error.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

const std::string kNode = "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";

TEST(MeshTetgen, NumbersFromTheFirstNodeAndReadsAttributesAndFaces) {
  // Numbered from 0 this time; one region attribute; a face with boundary marker 5.
  const std::string node = "# comment\n4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n";
  const std::string ele = "1 4 1\n0 0 1 2 3 9\n";
  const std::string face = "1 1\n0 0 1 2 5\n";
  const CellMesh m = parse_tetgen(node, "b.node", ele, "b.ele", face, "b.face");
  ASSERT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.vertices[1], Vec3(1, 0, 0));
  ASSERT_EQ(m.cells.size(), 2u);
  EXPECT_EQ(m.cells[0].shape, CellShape::tetra);
  EXPECT_EQ(m.cells[0].corners, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(m.cells[0].region, 9);
  EXPECT_EQ(m.cells[1].shape, CellShape::triangle);
  EXPECT_EQ(m.cells[1].region, 5);
  const auto regions = region_nodes(m);
  EXPECT_EQ(regions.at(5), (std::vector<int>{0, 1, 2}));
}

TEST(MeshTetgen, BadInputNamesTheLine) {
  EXPECT_EQ(test::input_error([&] { parse_tetgen(kNode, "b.node", "1 4 0\n1 1 2 3 4\n", "b.ele"); }), "");
  EXPECT_EQ(test::input_error([&] { parse_tetgen(kNode, "b.node", "1 4 0\n1 1 2 3 5\n", "b.ele"); }),
            "b.ele:2: node number 5 does not exist (nodes are 1..4)");
  // A tetrahedron against the first one's orientation loads, and is counted.
  EXPECT_EQ(parse_tetgen(kNode, "b.node", "2 4 0\n1 1 2 3 4\n2 1 3 2 4\n", "b.ele").reoriented,
            1u);
}

}  // namespace
}  // namespace dampbound
