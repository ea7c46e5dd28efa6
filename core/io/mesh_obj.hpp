#pragma once
// Wavefront OBJ surface meshes as mass-spring models: one node per vertex, one spring per
// distinct edge of the faces (rest length = initial length), optionally a bending spring
// across every edge shared by two triangles, and anchors. What a scene's [mesh] table loads.
#include <string>
#include <vector>

#include "core/io/mesh.hpp"

namespace dampbound {

/// The geometry of an OBJ file: `v x y z` vertices and `f` faces (vertex indices from 0).
struct ObjMesh {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;
};

/// Parses OBJ text: `v` and `f` statements (face corners as `i`, `i/t`, `i//n` or `i/t/n`,
/// negative indices counting back from the last vertex); texture coordinates, normals,
/// groups, materials and other statements are ignored. Throws InputError "PATH:LINE: ..." on
/// a malformed vertex or face, a face with fewer than 3 corners, a corner repeated in a face,
/// an index out of range, or a file with no face.
ObjMesh parse_obj(const std::string& text, const std::string& path);

/// The faces as polygon cells (triangles, quads, larger polygons) of region 0; `where` of each
/// cell is its index among the faces.
CellMesh cells_from_obj(const ObjMesh& mesh);

/// model_from_mesh(cells_from_obj(mesh), how): quads get both diagonals and, with `bend`,
/// flexion springs; polygons of more than 4 corners get their sides only.
ModelSpec model_from_obj(const ObjMesh& mesh, const MeshSprings& how);

}  // namespace dampbound
