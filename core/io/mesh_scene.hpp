#pragma once
// A scene from a mesh given as arrays (points, cells by shape, a region tag per cell): what
// Python's Scene.from_arrays and Scene.from_meshio build, through the same checks and builder
// as the mesh file readers (docs/meshes.md, "Meshes from Python").
#include <string>
#include <vector>

#include "core/io/mesh.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// One block of cells of one shape: `corners` holds count x corner_count(shape) vertex
/// indices row by row (polygons: not taken), `regions` one tag per cell or nothing.
struct CellBlock {
  CellShape shape = CellShape::triangle;
  std::vector<int> corners;
  std::vector<int> regions;
};

/// What the mesh scene is made of beyond its springs: fixed regions and the perturbation.
struct MeshSceneOptions {
  MeshSprings springs;
  std::vector<int> fixed_regions;  ///< region tags whose nodes are fixed
  int perturb_node = -1;           ///< -1: no perturbation (the watched node is 0)
  Vec3 displacement = Vec3::Zero();
  std::string name = "mesh";
};

/// The scene, its default parameters and protocol, the body cells kept for ParaView. Every
/// cell is checked as a reader checks it; errors name the block and the cell ("tetra cell 12:
/// degenerate tetrahedron (zero volume)"). `reoriented` receives the count of tetrahedra
/// against the first one's orientation.
SceneSpec scene_from_arrays(const std::vector<Vec3>& points, const std::vector<CellBlock>& blocks,
                            const MeshSceneOptions& options, std::size_t* reoriented = nullptr);

/// CellShape of a meshio cell type name ("vertex", "line", "triangle", "quad", "tetra");
/// InputError naming the type otherwise.
CellShape shape_of_meshio(const std::string& type);

}  // namespace dampbound
