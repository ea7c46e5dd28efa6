// A scene from mesh arrays (core/io/mesh_scene.cpp): what Python's Scene.from_arrays and
// Scene.from_meshio build, and the errors that name the block and the cell.
#include "core/io/mesh_scene.hpp"

#include <gtest/gtest.h>

#include <string>

#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {

/// Two triangles sharing an edge: a unit square split along its diagonal, in regions 1 and 2.
std::vector<Vec3> square() {
  return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
}
CellBlock two_triangles() {
  CellBlock b;
  b.shape = CellShape::triangle;
  b.corners = {0, 1, 2, 0, 2, 3};
  b.regions = {1, 2};
  return b;
}

std::string mesh_error_of(const std::vector<Vec3>& points, const std::vector<CellBlock>& blocks,
                     const MeshSceneOptions& o = {}) {
  try {
    scene_from_arrays(points, blocks, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshScene, TwoTrianglesGiveTheirEdgesFixedRegionsAndThePerturbation) {
  MeshSceneOptions o;
  o.fixed_regions = {2};
  o.perturb_node = 1;
  o.displacement = Vec3(0, 0, 0.25);
  o.name = "square";
  const SceneSpec s = scene_from_arrays(square(), {two_triangles()}, o);
  EXPECT_EQ(s.name, "square");
  EXPECT_EQ(s.model.node_count(), 4);
  EXPECT_EQ(s.model.spring_count(), 5);  // four sides and the shared diagonal, once each
  // Region 2's triangle (0, 2, 3) is fixed; node 1 is not.
  EXPECT_EQ(s.model.fixed[0], 1);
  EXPECT_EQ(s.model.fixed[1], 0);
  EXPECT_EQ(s.model.fixed[2], 1);
  EXPECT_EQ(s.model.fixed[3], 1);
  ASSERT_EQ(s.perturbations.size(), 1u);
  EXPECT_EQ(s.watched, 1);
  EXPECT_DOUBLE_EQ(s.rules.reference, 0.25);
  EXPECT_EQ(s.body.size(), 2u);
}

TEST(MeshScene, BadArraysNameWhatToFix) {
  CellBlock b = two_triangles();
  EXPECT_EQ(mesh_error_of({}, {b}), "points: the mesh has no point");
  std::vector<Vec3> p = square();
  p[2].x() = std::nan("");
  EXPECT_EQ(mesh_error_of(p, {b}), "points: row 2 is not finite");
  b.corners.pop_back();
  EXPECT_EQ(mesh_error_of(square(), {b}), "triangle cells: 5 indices are not rows of 3");
  b = two_triangles();
  b.regions = {1};
  EXPECT_EQ(mesh_error_of(square(), {b}), "triangle cells: 1 region tags for 2 cells");
  b = two_triangles();
  b.corners[4] = 0;  // triangle 1 becomes (0, 0, 3)
  EXPECT_EQ(mesh_error_of(square(), {b}).rfind("triangle cell 1: ", 0), 0u);
  MeshSceneOptions o;
  o.fixed_regions = {7};
  EXPECT_EQ(mesh_error_of(square(), {two_triangles()}, o), "fixed: no cell has region tag 7");
  o = {};
  o.perturb_node = 9;
  EXPECT_EQ(mesh_error_of(square(), {two_triangles()}, o),
            "perturb: node 9 does not exist (4 nodes)");
}

TEST(MeshScene, MeshioTypeNames) {
  EXPECT_EQ(shape_of_meshio("vertex"), CellShape::point);
  EXPECT_EQ(shape_of_meshio("line"), CellShape::line);
  EXPECT_EQ(shape_of_meshio("triangle"), CellShape::triangle);
  EXPECT_EQ(shape_of_meshio("quad"), CellShape::quad);
  EXPECT_EQ(shape_of_meshio("tetra"), CellShape::tetra);
  EXPECT_THROW(shape_of_meshio("hexahedron"), InputError);
}

}  // namespace
}  // namespace dampbound
