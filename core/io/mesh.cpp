#include "core/io/mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "core/io/format.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {

using Edge = std::pair<int, int>;
Edge edge(int a, int b) {
  return {std::min(a, b), std::max(a, b)};
}


/// Twice the vector area of a polygon (the sum of the cross products of a fan from corner 0).
Vec3 vector_area2(const std::vector<Vec3>& p, const std::vector<int>& c) {
  Vec3 a = Vec3::Zero();
  for (size_t k = 1; k + 1 < c.size(); ++k)
    a += (p[size_t(c[k])] - p[size_t(c[0])]).cross(p[size_t(c[k + 1])] - p[size_t(c[0])]);
  return a;
}

/// Volume (tetrahedra, cm^3) or area (surfaces, cm^2) of a cell; 0 for points and lines.
double measure(const std::vector<Vec3>& p, const MeshCell& c) {
  const auto& k = c.corners;
  switch (c.shape) {
    case CellShape::tetra:
      return std::abs(
          tetra_signed_volume(p[size_t(k[0])], p[size_t(k[1])], p[size_t(k[2])], p[size_t(k[3])]));
    case CellShape::quad:  // half the cross product of the diagonals: exact for planar quads
      return 0.5 *
             (p[size_t(k[2])] - p[size_t(k[0])]).cross(p[size_t(k[3])] - p[size_t(k[1])]).norm();
    case CellShape::triangle:
    case CellShape::polygon:
      return 0.5 * vector_area2(p, k).norm();
    default:
      return 0;
  }
}

/// The springs a body cell holds: its edges, and for a quad its two diagonals.
std::vector<Edge> cell_springs(const MeshCell& c) {
  const auto& k = c.corners;
  if (c.shape == CellShape::tetra)
    return {{k[0], k[1]}, {k[1], k[2]}, {k[2], k[0]}, {k[0], k[3]}, {k[1], k[3]}, {k[2], k[3]}};
  std::vector<Edge> out;
  for (size_t i = 0; i < k.size(); ++i) out.emplace_back(k[i], k[(i + 1) % k.size()]);
  if (c.shape == CellShape::quad) {  // shear: both diagonals
    out.emplace_back(k[0], k[2]);
    out.emplace_back(k[1], k[3]);
  }
  return out;
}

}  // namespace

size_t corner_count(CellShape s) {
  switch (s) {
    case CellShape::point:
      return 1;
    case CellShape::line:
      return 2;
    case CellShape::triangle:
      return 3;
    case CellShape::quad:
      return 4;
    case CellShape::tetra:
      return 4;
    case CellShape::polygon:
      return 0;  // any count >= 3
  }
  return 0;
}

int cell_dimension(CellShape shape) {
  switch (shape) {
    case CellShape::point:
      return 0;
    case CellShape::line:
      return 1;
    case CellShape::tetra:
      return 3;
    default:
      return 2;
  }
}

const char* to_string(CellShape shape) {
  switch (shape) {
    case CellShape::point:
      return "point";
    case CellShape::line:
      return "line";
    case CellShape::triangle:
      return "triangle";
    case CellShape::quad:
      return "quadrilateral";
    case CellShape::polygon:
      return "polygon";
    case CellShape::tetra:
      return "tetrahedron";
  }
  return "?";
}

double tetra_signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

std::optional<std::string> cell_problem(const std::vector<Vec3>& vertices,
                                        const MeshCell& cell) {
  const auto& k = cell.corners;
  const size_t want = corner_count(cell.shape);
  if ((want && k.size() != want) || (!want && k.size() < 3))
    return std::string("a ") + to_string(cell.shape) + " needs " +
           (want ? std::to_string(want) : std::string("at least 3")) + " nodes, not " +
           std::to_string(k.size());
  for (int v : k)
    if (v < 0 || size_t(v) >= vertices.size())
      return "node index " + std::to_string(v) + " is out of range (" +
             std::to_string(vertices.size()) + " nodes)";
  std::vector<int> sorted = k;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    return std::string("a ") + to_string(cell.shape) + " uses the same node twice";
  double longest = 0;
  for (size_t i = 0; i < k.size(); ++i)
    for (size_t j = i + 1; j < k.size(); ++j)
      longest = std::max(longest, (vertices[size_t(k[i])] - vertices[size_t(k[j])]).norm());
  const int dim = cell_dimension(cell.shape);
  if (dim == 0) return std::nullopt;
  const double size = dim == 1 ? longest : measure(vertices, cell);
  // Relative to the longest edge: 1e-12 of a regular element's measure is degenerate.
  if (!(size > 1e-12 * std::pow(longest, dim)))
    return std::string("degenerate ") + to_string(cell.shape) + " (zero " +
           (dim == 3   ? "volume"
            : dim == 2 ? "area"
                       : "length") +
           ")";
  return std::nullopt;
}

int tetra_orientation(const std::vector<Vec3>& vertices, const MeshCell& cell) {
  if (cell.shape != CellShape::tetra || cell_problem(vertices, cell)) return 0;
  const auto& k = cell.corners;
  return tetra_signed_volume(vertices[size_t(k[0])], vertices[size_t(k[1])],
                             vertices[size_t(k[2])], vertices[size_t(k[3])]) > 0
             ? 1
             : -1;
}

std::optional<std::string> accept_cell(CellMesh& mesh, const MeshCell& cell, int& orientation) {
  if (auto why = cell_problem(mesh.vertices, cell)) return why;
  if (const int o = tetra_orientation(mesh.vertices, cell)) {
    if (orientation == 0) orientation = o;
    if (o != orientation) ++mesh.reoriented;
  }
  return std::nullopt;
}

std::string reoriented_note(const CellMesh& mesh, const std::string& file) {
  if (mesh.reoriented == 0) return "";
  size_t tets = 0;
  for (const MeshCell& c : mesh.cells) tets += c.shape == CellShape::tetra;
  return file + ": note: " + std::to_string(mesh.reoriented) + " of " + std::to_string(tets) +
         " tetrahedra list their corners in the other orientation; taken as they are (masses "
         "and stiffnesses use |V|)";
}

void check_mesh(const CellMesh& mesh, const std::function<std::string(const MeshCell&)>& where) {
  int top = -1;
  for (const MeshCell& c : mesh.cells) top = std::max(top, cell_dimension(c.shape));
  if (top < 2)
    throw InputError(where(MeshCell{}) +
                     ": the mesh has no triangle, quadrilateral or "
                     "tetrahedron");
  std::vector<std::uint8_t> in_body(mesh.vertices.size(), 0);
  for (const MeshCell& c : mesh.cells)
    if (cell_dimension(c.shape) == top)
      for (int v : c.corners) in_body[size_t(v)] = 1;
  for (const MeshCell& c : mesh.cells)
    if (cell_dimension(c.shape) < top)
      for (int v : c.corners)
        if (!in_body[size_t(v)])
          throw InputError(where(c) + ": mixed dimensions: this " + to_string(c.shape) +
                           " has node " + std::to_string(v) + ", which no " +
                           (top == 3 ? "tetrahedron" : "face") + " uses");
}

ModelSpec model_from_mesh(const CellMesh& mesh, const MeshSprings& how) {
  ModelSpec m;
  std::vector<Vec3> p;
  for (const Vec3& v : mesh.vertices) {
    p.push_back(v * how.scale);
    const int i = add_node(m, p.back());
    m.anchor_scale[size_t(i)] = how.anchors ? 1.0 : 0.0;
  }
  int top = 0;
  for (const MeshCell& c : mesh.cells) top = std::max(top, cell_dimension(c.shape));
  std::map<Edge, size_t> index;               // spring of each edge
  std::vector<double> held;                   // per spring: measure of the cells holding it
  std::map<Edge, std::vector<size_t>> sides;  // per side of a surface cell: the cells on it
  std::vector<double> lumped(p.size(), 0.0);
  const auto spring = [&](int a, int b, double w) {
    const auto [it, fresh] = index.emplace(edge(a, b), m.springs.size());
    if (fresh) {
      add_spring(m, a, b, 1.0);
      held.push_back(0);
    }
    held[it->second] += w;
    return fresh;
  };
  for (size_t ci = 0; ci < mesh.cells.size(); ++ci) {
    const MeshCell& c = mesh.cells[ci];
    if (cell_dimension(c.shape) != top) continue;  // lower dimensions only tag regions
    const double w = measure(p, c);
    for (int v : c.corners) lumped[size_t(v)] += w / double(c.corners.size());
    for (const Edge& e : cell_springs(c)) spring(e.first, e.second, w);
    if (top == 2)
      for (size_t k = 0; k < c.corners.size(); ++k)
        sides[edge(c.corners[k], c.corners[(k + 1) % c.corners.size()])].push_back(ci);
  }
  if (how.bend && top == 2) {
    std::vector<Edge> order(index.size());  // the edges in spring order
    for (const auto& [e, k] : index) order[k] = e;
    for (const Edge& e : order) {
      const auto it = sides.find(e);
      if (it == sides.end() || it->second.size() != 2) continue;
      const MeshCell& f = mesh.cells[it->second[0]];
      const MeshCell& g = mesh.cells[it->second[1]];
      const double w = measure(p, f) + measure(p, g);
      // The corner of a face next to `v` that is not `other` (triangles: the far corner).
      const auto beside = [](const MeshCell& c, int v, int other) {
        const size_t n = c.corners.size();
        const size_t k =
            size_t(std::find(c.corners.begin(), c.corners.end(), v) - c.corners.begin());
        const int prev = c.corners[(k + n - 1) % n], next = c.corners[(k + 1) % n];
        return prev == other ? next : prev;
      };
      if (f.shape == CellShape::triangle && g.shape == CellShape::triangle) {
        const int a = beside(f, e.second, e.first), b = beside(g, e.second, e.first);
        if (a != b && !index.count(edge(a, b))) spring(a, b, w);
      } else if (f.shape == CellShape::quad && g.shape == CellShape::quad) {
        for (int end : {e.first, e.second}) {
          const int other = end == e.first ? e.second : e.first;
          const int a = beside(f, end, other), b = beside(g, end, other);
          if (a != b && !index.count(edge(a, b))) spring(a, b, w);
        }
      }
    }
  }
  if (how.density > 0)
    for (size_t i = 0; i < p.size(); ++i) {
      if (!(lumped[i] > 0))
        throw InputError("node " + std::to_string(i) +
                         " belongs to no element, so its lumped mass would be 0");
      m.mass_scale[i] = how.density * lumped[i];
    }
  if (how.young > 0)
    for (size_t k = 0; k < m.springs.size(); ++k) {
      const double l = m.springs[k].rest_length;
      if (!(l > 0))
        throw InputError("the spring " + std::to_string(m.springs[k].i) + "-" +
                         std::to_string(m.springs[k].j) + " has rest length 0: no stiffness " +
                         "from the geometry (a degenerate face?)");
      m.springs[k].kappa_scale = how.young * held[k] / (l * l);
    }
  return m;
}

std::vector<BodyCell> body_cells(const CellMesh& mesh) {
  int top = 0;
  for (const MeshCell& c : mesh.cells) top = std::max(top, cell_dimension(c.shape));
  std::vector<BodyCell> out;
  for (const MeshCell& c : mesh.cells) {
    if (cell_dimension(c.shape) != top) continue;
    BodyCell b{top, c.corners};
    if (tetra_orientation(mesh.vertices, c) < 0) std::swap(b.corners[1], b.corners[2]);
    out.push_back(std::move(b));
  }
  return out;
}

std::map<int, std::vector<int>> region_nodes(const CellMesh& mesh) {
  std::map<int, std::set<int>> sets;
  for (const MeshCell& c : mesh.cells)
    if (c.region != 0) sets[c.region].insert(c.corners.begin(), c.corners.end());
  std::map<int, std::vector<int>> out;
  for (const auto& [tag, s] : sets) out[tag].assign(s.begin(), s.end());
  return out;
}

}  // namespace dampbound
