#pragma once
// TetGen .node/.ele(/.face) files (docs/meshes.md). The reader takes the file's bytes and a name for messages (fuzz
// targets need no files) and throws InputError "NAME:LINE: ..." or "NAME: byte N: ..." on the
// first problem.
#include <cstddef>
#include <string>

#include "core/io/mesh.hpp"

namespace dampbound {

/// TetGen: a .node file, a .ele file (4-node tetrahedra; the region attribute, when the
/// header declares attributes, is the region tag) and optionally a .face file (faces tag their
/// nodes with their boundary marker; empty `face` = none). Indices start at the first node's
/// number (0 or 1). Tetrahedra of the other orientation than
/// the first one's load and are counted in CellMesh::reoriented.
CellMesh parse_tetgen(const std::string& node, const std::string& node_name, const std::string& ele,
                      const std::string& ele_name, const std::string& face = {},
                      const std::string& face_name = {});

}  // namespace dampbound
