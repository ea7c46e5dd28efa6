#pragma once
// Wavefront OBJ surface meshes as mass-spring models: one node per vertex, one spring per
// distinct edge of the faces (rest length = initial length), optionally a bending spring
// across every edge shared by two triangles, and anchors. What a scene's [mesh] table loads.
#include <string>
#include <vector>

#include "core/model.hpp"

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

/// How a mesh becomes springs.
struct MeshSprings {
  double scale = 1.0;   ///< cm per OBJ unit
  bool bend = false;    ///< a spring between the far corners of two triangles sharing an edge
  bool anchors = true;  ///< an anchor at every vertex (anchor_scale 1)
};

/// The model of a mesh: nodes in vertex order, edge springs in order of first appearance in
/// the faces, then the bending springs (when asked) in the order of their edges; an edge
/// shared by more than two faces gets no bending spring, and a bending spring that would
/// repeat an existing spring is skipped.
Model model_from_obj(const ObjMesh& mesh, const MeshSprings& how);

}  // namespace dampbound
