#include "core/io/mesh_scene.hpp"

#include <cmath>

#include "dampbound/physics/error.hpp"

namespace dampbound {

CellShape shape_of_meshio(const std::string& type) {
  if (type == "vertex") return CellShape::point;
  if (type == "line") return CellShape::line;
  if (type == "triangle") return CellShape::triangle;
  if (type == "quad") return CellShape::quad;
  if (type == "tetra") return CellShape::tetra;
  throw InputError("cell type '" + type +
                   "' is not taken: only vertex, line, triangle, quad and tetra cells make "
                   "a mass-spring model");
}

SceneSpec scene_from_arrays(const std::vector<Vec3>& points, const std::vector<CellBlock>& blocks,
                            const MeshSceneOptions& options, std::size_t* reoriented) {
  CellMesh mesh;
  for (size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw InputError("points: row " + std::to_string(i) + " is not finite");
  mesh.vertices = points;
  if (points.empty()) throw InputError("points: the mesh has no point");
  int orientation = 0;
  for (const CellBlock& b : blocks) {
    const size_t per = corner_count(b.shape);
    const std::string block = std::string(to_string(b.shape));
    if (per == 0 || b.corners.size() % per)
      throw InputError(block + " cells: " + std::to_string(b.corners.size()) +
                       " indices are not rows of " + std::to_string(per));
    const size_t count = b.corners.size() / per;
    if (!b.regions.empty() && b.regions.size() != count)
      throw InputError(block + " cells: " + std::to_string(b.regions.size()) + " region tags for " +
                       std::to_string(count) + " cells");
    for (size_t k = 0; k < count; ++k) {
      MeshCell c;
      c.shape = b.shape;
      c.corners.assign(b.corners.begin() + long(k * per), b.corners.begin() + long((k + 1) * per));
      c.region = b.regions.empty() ? 0 : b.regions[k];
      c.where = static_cast<long long>(k);
      if (const auto why = accept_cell(mesh, c, orientation))
        throw InputError(block + " cell " + std::to_string(k) + ": " + *why);
      mesh.cells.push_back(std::move(c));
    }
  }
  check_mesh(mesh, [](const MeshCell& c) {
    return c.corners.empty() ? std::string("cells")
                             : std::string(to_string(c.shape)) + " cell " + std::to_string(c.where);
  });
  if (reoriented) *reoriented = mesh.reoriented;
  SceneSpec s;
  s.name = options.name;
  s.model = model_from_mesh(mesh, options.springs);
  s.body = body_cells(mesh);
  const auto regions = region_nodes(mesh);
  for (int tag : options.fixed_regions) {
    const auto it = regions.find(tag);
    if (it == regions.end())
      throw InputError("fixed: no cell has region tag " + std::to_string(tag));
    for (int i : it->second) s.model.fixed[size_t(i)] = 1;
  }
  if (options.perturb_node >= 0) {
    if (size_t(options.perturb_node) >= points.size())
      throw InputError("perturb: node " + std::to_string(options.perturb_node) +
                       " does not exist (" + std::to_string(points.size()) + " nodes)");
    if (s.model.fixed[size_t(options.perturb_node)])
      throw InputError("perturb: node " + std::to_string(options.perturb_node) + " is fixed");
    s.perturbations.push_back({options.perturb_node, options.displacement, Vec3::Zero()});
    s.watched = options.perturb_node;
    const double d = options.displacement.norm();
    if (d > 0) s.rules.reference = d;
  }
  return s;
}

}  // namespace dampbound
