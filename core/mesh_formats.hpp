#pragma once
// Volumetric and surface mesh files beside OBJ (docs/meshes.md): Gmsh MSH 2.2 and 4.1 (ASCII
// and binary), TetGen .node/.ele(/.face) and VTK legacy unstructured grids (ASCII). Each
// reader takes the file's bytes and a name for messages, so fuzz targets need no files, and
// throws InputError "NAME:LINE: ..." or "NAME: byte N: ..." on the first problem.
#include <cstddef>
#include <string>

#include "core/mesh.hpp"

namespace dampbound {

/// Gmsh MSH 2.2 or 4.1, ASCII or binary (little-endian, 8-byte doubles). Elements: points
/// (15), lines (1), triangles (2), quadrangles (3), tetrahedra (4); any other type is an
/// error. Region tag = the element's physical group (2.2: its first tag; 4.1: the first
/// physical tag of its entity); $PhysicalNames fill region_names. Tetrahedra must have a
/// positive Jacobian (Gmsh's convention).
CellMesh parse_msh(const char* data, size_t size, const std::string& name);

/// TetGen: a .node file, a .ele file (4-node tetrahedra; the region attribute, when the
/// header declares attributes, is the region tag) and optionally a .face file (faces tag their
/// nodes with their boundary marker; empty `face` = none). Indices start at the first node's
/// number (0 or 1). Every tetrahedron must have the orientation of the first one.
CellMesh parse_tetgen(const std::string& node, const std::string& node_name, const std::string& ele,
                      const std::string& ele_name, const std::string& face = {},
                      const std::string& face_name = {});

/// A VTK legacy file (versions 2 to 5.1, ASCII) with DATASET UNSTRUCTURED_GRID. Cell types
/// vertex (1), line (3), triangle (5), polygon (7), quad (9), tetra (10). Region tag = the
/// integer cell array named `region_array` (SCALARS or FIELD; empty = the first
/// one-component cell array, if any). Tetrahedra must have a positive orientation (VTK's).
CellMesh parse_vtk(const char* data, size_t size, const std::string& name,
                   const std::string& region_array = {});

/// The formats by key: "obj", "msh", "tetgen", "vtk"; from a file name's extension when
/// `format` is empty (.obj, .msh, .node/.ele, .vtk). Empty when unknown.
std::string mesh_format(const std::string& path, const std::string& format = {});

/// Reads a mesh file of any format (`format` as for mesh_format). For TetGen, `path` may name
/// the .node or the .ele file; the other and a .face file beside it are read too.
CellMesh read_mesh_file(const std::string& path, const std::string& format = {},
                        const std::string& region_array = {});

}  // namespace dampbound
