// A scene's [mesh] table and its [[mesh_region]] tables (docs/meshes.md):
// the mesh file through its format's reader, units, springs, geometric masses and
// stiffnesses, and the file's own regions (Gmsh physical groups, TetGen region attributes
// and boundary markers, VTK cell data) mapped to fixed nodes, scales and a probe's pull.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>

#include "core/io/detail/scene_mesh.hpp"
#include "core/io/detail/scene_reader.hpp"
#include "core/io/files.hpp"
#include "core/io/mesh_file.hpp"
#include "core/io/scene_text.hpp"

namespace dampbound::scene_file {
namespace {

/// The nodes of the region a [[mesh_region]] names by `tag` or by `name` (Gmsh physical name).
const std::vector<int>& region_of(const Reader& r, const toml::table& t, const CellMesh& mesh,
                                  const std::map<int, std::vector<int>>& regions) {
  const toml::node* tn = t.get("tag");
  const toml::node* nn = t.get("name");
  if ((tn != nullptr) == (nn != nullptr)) r.fail(t, "[[mesh_region]] needs one of tag or name");
  int tag = 0;
  if (tn) {
    tag = static_cast<int>(r.integer(*tn, "tag"));
  } else {
    const std::string name = r.string(*nn, "name");
    const auto it = mesh.region_names.find(name);
    if (it == mesh.region_names.end()) {
      std::string known;
      for (const auto& [n, k] : mesh.region_names) known += (known.empty() ? "" : ", ") + n;
      r.fail(*nn,
             "the mesh has no region named '" + name + "'" +
                 (known.empty() ? std::string(" (it names none)") : " (it has " + known + ")"));
    }
    tag = it->second;
  }
  const auto it = regions.find(tag);
  if (it == regions.end()) {
    std::string known;
    for (const auto& [k, nodes] : regions) known += (known.empty() ? "" : ", ") + std::to_string(k);
    r.fail(tn ? *tn : *nn,
           "no element of the mesh has region tag " + std::to_string(tag) +
               (known.empty() ? std::string(" (it has none)") : " (it has " + known + ")"));
  }
  return it->second;
}

/// [[mesh_region]]: multiplies the scales of its nodes (and of the springs with both ends in
/// it), fixes them, gives them an external force, or pulls each by `displacement` at t = 0.
void read_mesh_regions(const Reader& r, const toml::table& root, const CellMesh& mesh,
                       SceneSpec& s) {
  const auto regions = region_nodes(mesh);
  for (const toml::table& t : r.tables(root, "mesh_region")) {
    const std::vector<int>& nodes = region_of(r, t, mesh, regions);
    ModelSpec& m = s.model;
    {
      SceneRegion named;
      if (auto* n = t.get("name")) named.label = r.string(*n, "name");
      else named.label = "tag " + std::to_string(r.integer(*t.get("tag"), "tag"));
      named.nodes = nodes;
      std::sort(named.nodes.begin(), named.nodes.end());
      s.regions.push_back(std::move(named));
    }
    for (int i : nodes) {
      const auto k = static_cast<size_t>(i);
      if (auto* n = t.get("fixed")) m.fixed[k] = r.boolean(*n, "fixed");
      if (auto* n = t.get("mass_scale")) m.mass_scale[k] *= r.positive(*n, "mass_scale");
      if (auto* n = t.get("gamma_scale")) m.gamma_scale[k] *= r.non_negative(*n, "gamma_scale");
      if (auto* n = t.get("anchor_scale")) m.anchor_scale[k] = r.non_negative(*n, "anchor_scale");
      if (auto* n = t.get("force")) m.external_force[k] = r.vec3(*n, "force");
    }
    if (auto* n = t.get("kappa_scale")) {
      const double ks = r.positive(*n, "kappa_scale");
      const std::set<int> in(nodes.begin(), nodes.end());
      for (Spring& sp : m.springs)
        if (in.count(sp.i) && in.count(sp.j)) sp.kappa_scale *= ks;
    }
    if (auto* n = t.get("kd_scale")) {  // the dashpots of its springs and anchors (SPEC 10)
      const double ds = r.non_negative(*n, "kd_scale");
      const std::set<int> in(nodes.begin(), nodes.end());
      for (Spring& sp : m.springs)
        if (in.count(sp.i) && in.count(sp.j)) sp.kd_scale *= ds;
      m.anchor_kd_scale.resize(m.rest.size(), 1.0);
      for (int i : nodes) m.anchor_kd_scale[static_cast<size_t>(i)] *= ds;
    }
    if (auto* n = t.get("displacement")) {
      const Vec3 d = r.vec3(*n, "displacement");
      for (int i : nodes) {
        if (m.fixed[static_cast<size_t>(i)])
          r.fail(*n, "the region's node " + std::to_string(i) + " is fixed");
        s.perturbations.push_back({i, d, Vec3::Zero()});
      }
    }
  }
}

}  // namespace

void read_mesh(const Reader& r, const toml::table& root, SceneSpec& s) {
  const toml::table& t = r.table(*root.get("mesh"), "mesh");
  r.check_keys(t, "[mesh]");
  const toml::node& fn = r.required(t, "file", "[mesh]");
  std::string file = r.string(fn, "file");
  if (file.empty()) r.fail(fn, "file must name a mesh file");
  const std::string named = file;
  try {  // docs/hardening.md: in the scene's folder unless --allow-any-path
    file = scene_relative_path(r.path(), named);
  } catch (const InputError& e) {
    r.fail(fn, "mesh file '" + named + "' " + e.what());
  }
  std::string format;
  if (auto* n = t.get("format")) {
    format = r.string(*n, "format");
    if (!mesh_format(file, format) || format == "node" || format == "ele")
      r.fail(*n, "format must be one of obj, msh, tetgen, vtk");
  } else if (!mesh_format(file)) {
    r.fail(fn, "cannot tell the format of " + file +
                   " from its extension: set format = \"obj\", "
                   "\"msh\", \"tetgen\" or \"vtk\"");
  }
  std::string region_array;
  if (auto* n = t.get("region_array")) region_array = r.string(*n, "region_array");
  MeshSprings how;
  if (auto* n = t.get("scale")) how.scale = r.positive(*n, "scale");
  if (auto* n = t.get("bend")) how.bend = r.boolean(*n, "bend");
  if (auto* n = t.get("anchors")) how.anchors = r.boolean(*n, "anchors");
  if (auto* n = t.get("density")) how.density = r.positive(*n, "density");
  if (auto* n = t.get("young")) how.young = r.positive(*n, "young");
  if (mesh_format(file, format) != "tetgen") {
    try {
      check_regular_input(file);  // a FIFO would block, a directory is no mesh
    } catch (const InputError& e) {
      r.fail(fn, "cannot read the mesh file: " + std::string(e.what()));
    }
  }
  const CellMesh mesh = read_mesh_file(file, format, region_array);  // errors name the mesh file
  if (const std::string note = reoriented_note(mesh, file); !note.empty())
    std::fprintf(stderr, "%s\n", note.c_str());  // said once, where the scene is loaded
  try {
    s.model = model_from_mesh(mesh, how);
  } catch (const InputError& e) {
    throw InputError(file + ": " + e.what());
  }
  s.body = body_cells(mesh);
  read_mesh_regions(r, root, mesh, s);
}

}  // namespace dampbound::scene_file
