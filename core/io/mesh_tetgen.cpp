// TetGen's .node, .ele and .face files (TetGen manual, section 5 "File Formats"): '#'
// comments, a header line, then one numbered record per line.
#include <cmath>
#include <utility>

#include "core/io/detail/mesh_scan.hpp"
#include "core/io/mesh_tetgen.hpp"

namespace dampbound {
namespace {

/// An attribute or marker used as a region tag: an integer value.
int region_value(MeshScan& s, double v) {
  if (v != std::floor(v) || std::abs(v) > 2e9) s.fail("a region attribute must be an integer");
  return static_cast<int>(v);
}

/// Reads `count` node numbers and maps them to vertex indices from `base`.
std::vector<int> corners(MeshScan& s, int count, long long base, size_t vertices) {
  std::vector<int> out;
  for (int k = 0; k < count; ++k) {
    const long long v = s.integer("a node number") - base;
    if (v < 0 || static_cast<size_t>(v) >= vertices)
      s.fail("node number " + std::to_string(v + base) + " does not exist (nodes are " +
             std::to_string(base) + ".." +
             std::to_string(base + static_cast<long long>(vertices) - 1) + ")");
    out.push_back(static_cast<int>(v));
  }
  return out;
}

}  // namespace

CellMesh parse_tetgen(const std::string& node, const std::string& node_name, const std::string& ele,
                      const std::string& ele_name, const std::string& face,
                      const std::string& face_name) {
  CellMesh mesh;
  long long base = 0;
  {
    MeshScan s(node.data(), node.size(), node_name);
    s.set_comments(true);
    const long long n = s.integer("the number of points");
    check_count(s, n, 8, "points");
    if (s.integer("the dimension") != 3) s.fail("the dimension must be 3");
    const long long attributes = s.integer_in("the number of attributes", 0, 1000);
    const long long markers = s.integer_in("the boundary marker flag", 0, 1);
    for (long long k = 0; k < n; ++k) {
      const long long id = s.integer("a point number");
      if (k == 0) {
        if (id != 0 && id != 1) s.fail("the first point must be numbered 0 or 1");
        base = id;
      } else if (id != base + k) {
        s.fail("point number " + std::to_string(id) + " out of sequence (" +
               std::to_string(base + k) + " expected)");
      }
      const double x = s.number("x"), y = s.number("y"), z = s.number("z");
      for (long long a = 0; a < attributes + markers; ++a) s.number("an attribute");
      mesh.vertices.emplace_back(x, y, z);
    }
    if (!s.at_end()) s.fail("more lines than the header's " + std::to_string(n) + " points");
  }
  MeshScan s(ele.data(), ele.size(), ele_name);
  s.set_comments(true);
  const long long n = s.integer("the number of tetrahedra");
  check_count(s, n, 8, "tetrahedra");
  const long long per = s.integer("nodes per tetrahedron");
  if (per != 4)
    s.fail("only 4-node tetrahedra are read (the header says " + std::to_string(per) + ")");
  const long long attributes = s.integer_in("the region attribute flag", 0, 1000);
  int orientation = 0;
  for (long long k = 0; k < n; ++k) {
    const long long at = s.mark();
    s.integer("a tetrahedron number");
    MeshCell c;
    c.shape = CellShape::tetra;
    c.where = at;
    c.corners = corners(s, 4, base, mesh.vertices.size());
    for (long long a = 0; a < attributes; ++a) {
      const double v = s.number("a region attribute");
      if (a == 0) c.region = region_value(s, v);
    }
    // TetGen writes one orientation for the whole mesh: the first tetrahedron's is the
    // reference, and a tetrahedron of the other sign is counted.
    if (const auto why = accept_cell(mesh, c, orientation)) s.fail_at(at, *why);
    mesh.cells.push_back(std::move(c));
  }
  if (!s.at_end()) s.fail("more lines than the header's " + std::to_string(n) + " tetrahedra");
  if (!face.empty()) {
    MeshScan f(face.data(), face.size(), face_name);
    f.set_comments(true);
    const long long nf = f.integer("the number of faces");
    check_count(f, nf, 8, "faces");
    const long long markers = f.integer_in("the boundary marker flag", 0, 1);
    for (long long k = 0; k < nf; ++k) {
      const long long at = f.mark();
      f.integer("a face number");
      MeshCell c;
      c.shape = CellShape::triangle;
      c.where = at;
      c.corners = corners(f, 3, base, mesh.vertices.size());
      if (markers) c.region = region_value(f, static_cast<double>(f.integer("a boundary marker")));
      if (const auto why = cell_problem(mesh.vertices, c)) f.fail_at(at, *why);
      mesh.cells.push_back(std::move(c));
    }
    if (!f.at_end()) f.fail("more lines than the header's " + std::to_string(nf) + " faces");
  }
  // Tetrahedra come first, faces after: a cell's file follows from its shape.
  check_mesh(mesh, [&](const MeshCell& c) {
    if (c.shape == CellShape::triangle) return face_name + ":" + std::to_string(c.where);
    return ele_name + ":" + std::to_string(c.where ? c.where : 1);
  });
  return mesh;
}

}  // namespace dampbound
