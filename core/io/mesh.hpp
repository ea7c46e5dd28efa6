#pragma once
// The mesh every reader fills (OBJ, Gmsh MSH, TetGen, VTK legacy) and the one builder that
// turns it into a mass-spring model: a node per vertex, a spring per unique element edge, both
// diagonals of each quad (shear), bending springs across the shared edges of a surface, and
// optionally masses and stiffnesses derived from the geometry (docs/meshes.md).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "dampbound/physics/model.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// The element kinds the readers accept. Points and lines only ever tag nodes for regions.
enum class CellShape : std::uint8_t { point, line, triangle, quad, polygon, tetra };

/// Corners of a cell of this shape (point 1, line 2, triangle 3, quad and tetra 4); 0 for a
/// polygon, which has any count >= 3.
std::size_t corner_count(CellShape s);

/// 0 for points, 1 for lines, 2 for triangles, quads and polygons, 3 for tetrahedra.
int cell_dimension(CellShape shape);
/// "point", "line", "triangle", "quadrilateral", "polygon", "tetrahedron".
const char* to_string(CellShape shape);

/// One element: its corners (vertex indices from 0), a region tag (0 = none; a Gmsh physical
/// group, a TetGen region attribute or boundary marker, a VTK cell-data value) and where it
/// was read (a line, or a byte offset in a binary file), for messages.
struct MeshCell {
  CellShape shape = CellShape::triangle;
  std::vector<int> corners;
  int region = 0;
  long long where = 0;
};

/// A mesh as read from a file. Cells of the highest dimension are the body (they make springs,
/// masses and stiffnesses); cells of lower dimension only tag their nodes with a region.
struct CellMesh {
  std::vector<Vec3> vertices;
  std::vector<MeshCell> cells;
  std::map<std::string, int> region_names;  ///< Gmsh physical names -> tags
  /// Tetrahedra whose corners run against the format's orientation (Gmsh and VTK: positive
  /// signed volume; TetGen: the first tetrahedron's sign). They are kept as listed: springs do
  /// not care, and masses and stiffnesses use |V|.
  std::size_t reoriented = 0;
};

/// Why a cell cannot be used, or "" when it can: a corner out of range or repeated, a wrong
/// corner count, or zero length / area / volume (relative to its longest edge). A
/// tetrahedron's orientation is no problem (see tetra_orientation).
std::optional<std::string> cell_problem(const std::vector<Vec3>& vertices,
                                        const MeshCell& cell);

/// +1 or -1: the sign of a usable tetrahedron's signed volume, det(x1-x0, x2-x0, x3-x0) / 6;
/// 0 for any other cell.
int tetra_orientation(const std::vector<Vec3>& vertices, const MeshCell& cell);

/// The readers' one step per cell: throws nothing, returns cell_problem(); when the cell is
/// usable and a tetrahedron against `orientation` (+1 or -1; 0 sets it from this cell),
/// counts it in mesh.reoriented.
std::optional<std::string> accept_cell(CellMesh& mesh, const MeshCell& cell, int& orientation);

/// "FILE: note: N of M tetrahedra ... ", or "" when none was reoriented: what a loader says
/// once per mesh.
std::string reoriented_note(const CellMesh& mesh, const std::string& file);

/// The signed volume of a tetrahedron (cm^3 when the positions are in cm): det / 6.
double tetra_signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// The final checks every reader runs: at least one cell of dimension 2 or 3, and no node of
/// a lower-dimensional cell outside the body (a surface hanging off a volume is a mixed-
/// dimension mesh). `where` formats a cell's location ("FILE:LINE" or "FILE: byte N").
void check_mesh(const CellMesh& mesh, const std::function<std::string(const MeshCell&)>& where);

/// How a mesh becomes springs, masses and stiffnesses.
struct MeshSprings {
  double scale = 1.0;   ///< cm per file unit
  bool bend = false;    ///< bending springs across the shared edges of triangles and quads
  bool anchors = true;  ///< an anchor at every vertex (anchor_scale 1)
  /// > 0: lumped masses, mass_scale_i = density x the sum over the body cells at i of their
  /// measure (volume in cm^3, area in cm^2) / their corner count (mass unit / cm^3 or cm^2).
  double density = 0;
  /// > 0: kappa_scale_e = young x (sum of the measures of the body cells holding spring e) /
  /// l_e^2, after van Gelder (1998), in mass unit / (cm s^2) for volumes, mass unit / s^2 for
  /// surfaces. A bending spring is held by the two faces it crosses.
  double young = 0;
};

/// The model of a mesh: nodes in vertex order, then, in order of first appearance in the body
/// cells, each cell's edges (a quad's two diagonals after its four sides), then the bending
/// springs (when asked) in the order of their edges: across an edge shared by exactly two
/// triangles, the far corners; across an edge shared by exactly two quads, at each end the
/// neighbours on either side along the line through the edge (Provot's flexion springs). A
/// bending spring that would repeat an existing spring is skipped.
ModelSpec model_from_mesh(const CellMesh& mesh, const MeshSprings& how);

/// The body cells (those of the highest dimension) as a scene keeps them for output, each
/// tetrahedron listed with a positive signed volume (corners 1 and 2 swapped where needed).
std::vector<BodyCell> body_cells(const CellMesh& mesh);

/// For each region tag, the nodes of the cells (of any dimension) that carry it.
std::map<int, std::vector<int>> region_nodes(const CellMesh& mesh);

}  // namespace dampbound
