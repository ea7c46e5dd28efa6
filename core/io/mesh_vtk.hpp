#pragma once
// VTK legacy unstructured grids (docs/meshes.md). The reader takes the file's bytes and a name for messages (fuzz
// targets need no files) and throws InputError "NAME:LINE: ..." or "NAME: byte N: ..." on the
// first problem.
#include <cstddef>
#include <string>

#include "core/io/mesh.hpp"

namespace dampbound {

/// A VTK legacy file (versions 2 to 5.1, ASCII) with DATASET UNSTRUCTURED_GRID. Cell types
/// vertex (1), line (3), triangle (5), polygon (7), quad (9), tetra (10). Region tag = the
/// integer cell array named `region_array` (SCALARS or FIELD; empty = the first
/// one-component cell array, if any). Tetrahedra against VTK's positive orientation load and
/// are counted in CellMesh::reoriented.
CellMesh parse_vtk(const char* data, size_t size, const std::string& name,
                   const std::string& region_array = {});

}  // namespace dampbound
