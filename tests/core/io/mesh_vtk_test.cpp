// VTK legacy unstructured grids (core/io/mesh_vtk.hpp): cells, the region array, and the
// bad-input cases naming the line.
#include "core/io/mesh_vtk.hpp"

#include <gtest/gtest.h>

#include <string>

#include "dampbound/physics/error.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

std::string vtk_error(const std::string& text) {
  return test::input_error([&] { parse_vtk(text.data(), text.size(), "m.vtk"); });
}

const std::string kTetra =
    "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n"
    "POINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nCELLS 1 5\n4 0 1 2 3\n"
    "CELL_TYPES 1\n";

TEST(MeshVtk, TetrahedronAndItsRegionArray) {
  const std::string text = kTetra + "10\nCELL_DATA 1\nSCALARS part int 1\nLOOKUP_TABLE default\n4\n";
  const CellMesh m = parse_vtk(text.data(), text.size(), "m.vtk");
  ASSERT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.vertices[2], Vec3(0, 1, 0));
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].shape, CellShape::tetra);
  EXPECT_EQ(m.cells[0].corners, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(m.cells[0].region, 4);  // the first one-component cell array
  // Asked for by name.
  const CellMesh named = parse_vtk(text.data(), text.size(), "m.vtk", "part");
  EXPECT_EQ(named.cells[0].region, 4);
}

TEST(MeshVtk, BadInputNamesTheLine) {
  EXPECT_EQ(vtk_error("$MeshFormat\n"),
            "m.vtk:1: not a VTK legacy file (no '# vtk DataFile Version' header)");
  EXPECT_EQ(vtk_error(kTetra + "10\n"), "");
  EXPECT_EQ(vtk_error(kTetra + "12\n"),
            "m.vtk:13: unsupported VTK cell type 12: only vertices (1), lines (3), triangles (5), "
            "polygons (7), quads (9) and tetrahedra (10) are read");
}

}  // namespace
}  // namespace dampbound
