// Scene.from_arrays and Scene.from_meshio: any mesh meshio reads (or arrays a code holds)
// as a scene, through the readers' checks and builder (core/io/mesh_scene.hpp).
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/io/format.hpp"
#include "core/io/mesh_scene.hpp"
#include "python/arrays.hpp"

namespace dampbound::python {
namespace {

/// Integers as the CLI's readers take them: an integer array, or a float one whose values are
/// all whole (meshio reads some formats' tags as float64; 2.7 is a ValueError naming `what`:
/// no truncation), each value within int32 (a ValueError naming the first that is not: no
/// wrap, 2**32 + 3 is not 3); a bool, complex or text array is a TypeError.
std::vector<int> ints_of(const py::handle& h, const std::string& what, py::ssize_t* rows = nullptr,
                         py::ssize_t* cols = nullptr) {
  py::array a = py::array::ensure(h);
  if (!a) throw py::type_error(what + ": expected an array of integers");
  const char kind = a.dtype().kind();
  const bool empty_list = a.size() == 0 && !py::isinstance<py::array>(h);
  if (kind != 'i' && kind != 'u' && kind != 'f' && !empty_list)
    throw py::type_error(what + ": expected an array of integers, got dtype " +
                         std::string(py::str(a.dtype())));
  if (kind == 'f') {  // whole numbers only, each as an int64 can hold it
    const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    for (py::ssize_t k = 0; k < d.size(); ++k) {
      const double v = d.data()[k];
      if (!(std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 9.2e18))
        throw py::value_error(what + ": " + format_number(v) + " at entry " + std::to_string(k) +
                              " is not a whole number");
    }
  }
  if (rows) *rows = a.ndim() ? a.shape(0) : 0;
  if (cols) *cols = a.ndim() == 2 ? a.shape(1) : 1;
  const bool unsigned_ = kind == 'u';
  const auto c = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(
      unsigned_ ? a.attr("astype")("uint64") : a.attr("astype")("int64"));
  std::vector<int> out(size_t(a.size()));
  for (py::ssize_t k = 0; k < c.size(); ++k) {
    const long long v = c.data()[k];
    const bool over = unsigned_ ? static_cast<unsigned long long>(v) > 2147483647ull
                                : v < -2147483648ll || v > 2147483647ll;
    if (over)
      throw py::value_error(what + ": " +
                            (unsigned_ ? std::to_string(static_cast<unsigned long long>(v))
                                       : std::to_string(v)) +
                            " at entry " + std::to_string(k) + " is outside the int32 range");
    out[size_t(k)] = int(v);
  }
  return out;
}

/// A geometry number as the scene files take it: finite, and > 0 (or >= 0 when `zero_ok`).
void require_number(double x, const char* name, bool zero_ok) {
  if (const auto why = number_problem(x, zero_ok)) throw py::value_error(std::string(name) + " " + *why);
}

/// (type, data) pairs from a dict {type: array}, a list of pairs, or meshio CellBlocks.
std::vector<std::pair<std::string, py::object>> blocks_of(const py::object& cells) {
  std::vector<std::pair<std::string, py::object>> out;
  if (py::isinstance<py::dict>(cells)) {
    for (auto kv : cells.cast<py::dict>())
      out.emplace_back(py::str(kv.first).cast<std::string>(),
                       py::reinterpret_borrow<py::object>(kv.second));
    return out;
  }
  const char* shapes =
      "cells: give a dict {type: (n, k) array} or a list of (type, array) pairs (types vertex, "
      "line, triangle, quad, tetra), e.g. {'triangle': [[0, 1, 2]]}";
  if (!py::isinstance<py::iterable>(cells) || py::isinstance<py::str>(cells))
    throw py::type_error(shapes);
  for (auto b : cells) {
    if (py::hasattr(b, "type") && py::hasattr(b, "data")) {
      out.emplace_back(py::str(b.attr("type")).cast<std::string>(), b.attr("data"));
      continue;
    }
    // A pair (type, array); a plain row of indices ([0, 1, 2]) names no type.
    const bool pair = (py::isinstance<py::tuple>(b) || py::isinstance<py::list>(b)) &&
                      py::len(b) == 2 && py::isinstance<py::str>(b[py::int_(0)]);
    if (!pair)
      throw py::type_error(std::string(shapes) + "; got a list whose item is " +
                           std::string(py::str(py::repr(b))).substr(0, 40) + " (no cell type)");
    out.emplace_back(b[py::int_(0)].cast<std::string>(),
                     py::reinterpret_borrow<py::object>(b[py::int_(1)]));
  }
  return out;
}

SceneSpec from_arrays(const py::object& points, const py::object& cells, const py::object& regions,
                      double scale, bool bend, bool anchors, double density, double young,
                      const std::vector<int>& fixed, const py::object& perturb,
                      const std::vector<double>& displacement, const std::string& name) {
  require_number(scale, "scale", false);
  require_number(density, "density", true);
  require_number(young, "young", true);
  py::array_t<double> keep;
  const NodeVectors p = node_vectors_of(points, "points", keep);
  std::vector<Vec3> pts(size_t(p.rows()));
  for (Eigen::Index i = 0; i < p.rows(); ++i) pts[size_t(i)] = p.row(i);
  const auto named = blocks_of(cells);
  std::vector<py::object> tags;  // per block, or none
  if (!regions.is_none()) {
    if (py::isinstance<py::dict>(regions)) {
      const auto d = regions.cast<py::dict>();
      for (const auto& [type, data] : named)
        tags.push_back(d.contains(type) ? py::reinterpret_borrow<py::object>(d[py::str(type)])
                                        : py::none());
    } else {
      for (auto r : regions) tags.push_back(py::reinterpret_borrow<py::object>(r));
      if (tags.size() != named.size())
        throw py::value_error("regions: " + std::to_string(tags.size()) + " arrays for " +
                              std::to_string(named.size()) + " cell blocks");
    }
  }
  std::vector<CellBlock> blocks;
  for (size_t k = 0; k < named.size(); ++k) {
    CellBlock b;
    b.shape = shape_of_meshio(named[k].first);
    py::ssize_t rows = 0, cols = 0;
    b.corners = ints_of(named[k].second, named[k].first + " cells", &rows, &cols);
    if (cols != py::ssize_t(corner_count(b.shape)))
      throw py::value_error(named[k].first + " cells: rows of " + std::to_string(cols) +
                            " indices, not " + std::to_string(corner_count(b.shape)));
    if (!tags.empty() && !tags[k].is_none())
      b.regions = ints_of(tags[k], named[k].first + " regions");
    blocks.push_back(std::move(b));
  }
  MeshSceneOptions o;
  o.springs.scale = scale;
  o.springs.bend = bend;
  o.springs.anchors = anchors;
  o.springs.density = density;
  o.springs.young = young;
  o.fixed_regions = fixed;
  if (!perturb.is_none()) {
    const std::vector<int> node = ints_of(py::make_tuple(perturb), "perturb");
    o.perturb_node = node[0];
  }
  if (displacement.size() != 3) throw py::value_error("displacement: give 3 numbers");
  o.displacement = Vec3(displacement[0], displacement[1], displacement[2]);
  o.name = name;
  size_t reoriented = 0;
  SceneSpec s = scene_from_arrays(pts, blocks, o, &reoriented);
  if (reoriented)
    PyErr_WarnEx(PyExc_UserWarning,
                 (std::to_string(reoriented) +
                  " tetrahedra list their corners in the other orientation; taken as they are "
                  "(masses and stiffnesses use |V|)")
                     .c_str(),
                 1);
  return s;
}

constexpr const char* kKeys =
    " scale: cm per unit; bend: bending springs across shared edges of faces; anchors: an "
    "anchor per node; density > 0: lumped masses from the geometry; young > 0: spring "
    "stiffnesses from it (docs/meshes.md); fixed: region tags whose nodes are fixed; perturb: "
    "the node moved by displacement at t = 0 (and watched).";

}  // namespace

void bind_meshes(py::module_& m) {
  py::object cls = m.attr("Scene");
  py::object staticmethod = py::module_::import("builtins").attr("staticmethod");
  cls.attr("from_arrays") = staticmethod(py::cpp_function(
      &from_arrays, py::name("from_arrays"), py::arg("points"), py::arg("cells"),
      py::arg("regions") = py::none(), py::kw_only(), py::arg("scale") = 1.0,
      py::arg("bend") = false, py::arg("anchors") = true, py::arg("density") = 0.0,
      py::arg("young") = 0.0, py::arg("fixed") = std::vector<int>{},
      py::arg("perturb") = py::none(), py::arg("displacement") = std::vector<double>{0, 0, 0},
      py::arg("name") = "mesh",
      (std::string("A scene from arrays: points (N, 3); cells a dict {type: (n, k) array} or a "
                   "list of (type, array) (types vertex, line, triangle, quad, tetra); regions "
                   "one integer tag per cell, as a dict by type or a list by block.") +
       kKeys)
          .c_str()));
  cls.attr("from_meshio") = staticmethod(py::cpp_function(
      [](const py::object& mesh, const py::object& region, double scale, bool bend, bool anchors,
         double density, double young, const std::vector<int>& fixed, const py::object& perturb,
         const std::vector<double>& displacement, const std::string& name) {
        py::object regions = py::none();
        const py::dict data = mesh.attr("cell_data");
        std::string key;
        if (!region.is_none()) {
          key = region.cast<std::string>();
          if (!data.contains(key))
            throw py::value_error("region: the mesh has no cell data '" + key + "'");
        } else {
          for (const char* k : {"gmsh:physical", "medit:ref", "region", "CellEntityIds"})
            if (data.contains(k)) {
              key = k;
              break;
            }
        }
        if (!key.empty()) regions = data[py::str(key)];
        return from_arrays(mesh.attr("points"), mesh.attr("cells"), regions, scale, bend, anchors,
                           density, young, fixed, perturb, displacement, name);
      },
      py::name("from_meshio"), py::arg("mesh"), py::arg("region") = py::none(), py::kw_only(),
      py::arg("scale") = 1.0, py::arg("bend") = false, py::arg("anchors") = true,
      py::arg("density") = 0.0, py::arg("young") = 0.0, py::arg("fixed") = std::vector<int>{},
      py::arg("perturb") = py::none(), py::arg("displacement") = std::vector<double>{0, 0, 0},
      py::arg("name") = "mesh",
      (std::string("A scene from a meshio.Mesh (any format meshio reads): its points and "
                   "cells; region tags from the cell data named `region` (default: the first "
                   "of gmsh:physical, medit:ref, region, CellEntityIds present).") +
       kKeys)
          .c_str()));
}

}  // namespace dampbound::python
