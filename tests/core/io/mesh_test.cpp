// The mesh builder (core/io/mesh.hpp): geometric masses and stiffnesses, quads' shear and
// flexion springs, cell checks.
#include "core/io/mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>

#include "core/io/mesh_file.hpp"
#include "core/io/mesh_obj.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

std::set<std::pair<int, int>> spring_set(const ModelSpec& m) {
  std::set<std::pair<int, int>> out;
  for (const Spring& s : m.springs) out.insert({std::min(s.i, s.j), std::max(s.i, s.j)});
  return out;
}

TEST(Mesh, LumpedMassesAndVolumeWeightedStiffness) {
  MeshSprings how;
  how.scale = 2.0;  // the block becomes 3 x 2 x 3 cm: 18 cm^3
  how.density = 0.5;
  how.young = 3.0;
  const ModelSpec m = model_from_mesh(read_mesh_file(test::source_path("tests/fuzz/corpus/msh/block-41.msh")), how);
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

TEST(Mesh, QuadsGetShearAndFlexionSprings) {
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

TEST(Mesh, CellChecks) {
  const std::vector<Vec3> v = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1),
                               Vec3(2, 0, 0)};
  EXPECT_DOUBLE_EQ(tetra_signed_volume(v[0], v[1], v[2], v[3]), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(tetra_signed_volume(v[0], v[2], v[1], v[3]), -1.0 / 6.0);
  MeshCell tet{CellShape::tetra, {0, 1, 2, 3}, 0, 1};
  EXPECT_FALSE(cell_problem(v, tet));
  EXPECT_EQ(tetra_orientation(v, tet), 1);
  MeshCell flipped{CellShape::tetra, {0, 2, 1, 3}, 0, 1};
  EXPECT_FALSE(cell_problem(v, flipped));  // orientation is no problem
  EXPECT_EQ(tetra_orientation(v, flipped), -1);
  CellMesh counted{v, {}, {}, 0};
  int convention = 1;
  EXPECT_FALSE(accept_cell(counted, tet, convention));
  EXPECT_FALSE(accept_cell(counted, flipped, convention));
  EXPECT_EQ(counted.reoriented, 1u);
  int first = 0;  // TetGen: the first tetrahedron sets it
  counted.reoriented = 0;
  EXPECT_FALSE(accept_cell(counted, flipped, first));
  EXPECT_FALSE(accept_cell(counted, tet, first));
  EXPECT_EQ(first, -1);
  EXPECT_EQ(counted.reoriented, 1u);
  MeshCell flat_tet{CellShape::tetra, {0, 1, 4, 2}, 0, 1};  // 0, 1, 4 on the x axis
  EXPECT_EQ(accept_cell(counted, flat_tet, first).value_or(""),
            "degenerate tetrahedron (zero volume)");
  EXPECT_EQ(tetra_orientation(v, flat_tet), 0);
  MeshCell flat{CellShape::triangle, {0, 1, 4}, 0, 1};  // three points on the x axis
  EXPECT_TRUE(cell_problem(v, flat));
  MeshCell out{CellShape::triangle, {0, 1, 7}, 0, 1};
  EXPECT_TRUE(cell_problem(v, out));
  MeshCell repeated{CellShape::triangle, {0, 1, 1}, 0, 1};
  EXPECT_TRUE(cell_problem(v, repeated));
  EXPECT_EQ(corner_count(CellShape::quad), 4u);
  EXPECT_EQ(corner_count(CellShape::polygon), 0u);
  EXPECT_EQ(cell_dimension(CellShape::tetra), 3);
  EXPECT_EQ(cell_dimension(CellShape::line), 1);
  EXPECT_STREQ(to_string(CellShape::quad), "quadrilateral");
}

TEST(Mesh, OneTetrahedronGivesSixSpringsInFirstAppearanceOrder) {
  CellMesh mesh;
  mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  mesh.cells.push_back(MeshCell{CellShape::tetra, {0, 1, 2, 3}, 0, 1});
  const ModelSpec m = model_from_mesh(mesh, MeshSprings{});
  EXPECT_EQ(m.node_count(), 4);
  EXPECT_EQ(m.spring_count(), 6);
  EXPECT_EQ(m.anchor_count(), 4);  // anchors = true by default
  EXPECT_EQ(spring_set(m).size(), 6u);
  for (const Spring& s : m.springs)
    EXPECT_DOUBLE_EQ(s.rest_length, (mesh.vertices[size_t(s.j)] - mesh.vertices[size_t(s.i)]).norm());
  MeshSprings no_anchors;
  no_anchors.anchors = false;
  EXPECT_EQ(model_from_mesh(mesh, no_anchors).anchor_count(), 0);
}

}  // namespace
}  // namespace dampbound
