#pragma once
// Mesh files of every format, by name: the format from the extension, then its reader.
#include <optional>
#include <string>

#include "core/io/mesh.hpp"

namespace dampbound {

/// The formats by key: "obj", "msh", "tetgen", "vtk"; from a file name's extension when
/// `format` is empty (.obj, .msh, .node/.ele, .vtk). nullopt when unknown.
std::optional<std::string> mesh_format(const std::string& path, const std::string& format = {});

/// Reads a mesh file of any format (`format` as for mesh_format). For TetGen, `path` may name
/// the .node or the .ele file; the other and a .face file beside it are read too.
CellMesh read_mesh_file(const std::string& path, const std::string& format = {},
                        const std::string& region_array = {});

}  // namespace dampbound
