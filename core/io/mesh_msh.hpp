#pragma once
// Gmsh MSH files (docs/meshes.md). The reader takes the file's bytes and a name for messages (fuzz
// targets need no files) and throws InputError "NAME:LINE: ..." or "NAME: byte N: ..." on the
// first problem.
#include <cstddef>
#include <string>

#include "core/io/mesh.hpp"

namespace dampbound {

/// Gmsh MSH 2.2 or 4.1, ASCII or binary (little-endian, 8-byte doubles). Elements: points
/// (15), lines (1), triangles (2), quadrangles (3), tetrahedra (4); any other type is an
/// error. Region tag = the element's physical group (2.2: its first tag; 4.1: the first
/// physical tag of its entity); $PhysicalNames fill region_names. Tetrahedra must have a
/// positive Jacobian (Gmsh's convention).
CellMesh parse_msh(const char* data, size_t size, const std::string& name);

}  // namespace dampbound
