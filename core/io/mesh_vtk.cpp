// VTK legacy unstructured grids, ASCII ("VTK File Formats", the legacy format, versions 2.0
// to 5.1: 5.1 writes CELLS as OFFSETS and CONNECTIVITY arrays).
#include <cmath>
#include <cstdlib>
#include <utility>

#include "core/io/detail/mesh_scan.hpp"
#include "core/io/mesh_vtk.hpp"

namespace dampbound {
namespace {

/// VTK cell type -> shape, or fails naming the type.
CellShape vtk_shape(MeshScan& s, long long type, long long at) {
  switch (type) {
    case 1:
      return CellShape::point;
    case 3:
      return CellShape::line;
    case 5:
      return CellShape::triangle;
    case 7:
      return CellShape::polygon;
    case 9:
      return CellShape::quad;
    case 10:
      return CellShape::tetra;
    default:
      break;
  }
  s.fail_at(at, "unsupported VTK cell type " + std::to_string(type) +
                    ": only vertices (1), lines (3), triangles (5), polygons (7), quads (9) and "
                    "tetrahedra (10) are read");
}

class VtkReader {
 public:
  VtkReader(const char* data, size_t size, const std::string& name, std::string region_array)
      : s_(data, size, name), wanted_(std::move(region_array)) {}

  CellMesh read() {
    const std::string head = s_.rest_of_line();
    if (head.rfind("# vtk DataFile Version", 0) != 0)
      s_.fail_at(1, "not a VTK legacy file (no '# vtk DataFile Version' header)");
    v5_ = head.find("Version 5") != std::string::npos;
    s_.rest_of_line();  // the title
    const std::string format = s_.word("ASCII or BINARY");
    if (format != "ASCII")
      s_.fail("only ASCII VTK files are read (found '" + format.substr(0, 20) + "')");
    if (s_.word("DATASET") != "DATASET" || s_.word("the dataset type") != "UNSTRUCTURED_GRID")
      s_.fail("only DATASET UNSTRUCTURED_GRID is read");
    std::vector<std::vector<int>> corners;
    std::vector<long long> where;
    while (!s_.at_end()) {
      const long long at = s_.mark();
      const std::string key = s_.word("a section");
      if (key == "POINTS") {
        const long long n = s_.integer("the number of points");
        check_count(s_, n, 6, "points");
        s_.word("the point type");
        for (long long k = 0; k < n; ++k) {
          const double x = s_.number("x"), y = s_.number("y"), z = s_.number("z");
          mesh_.vertices.emplace_back(x, y, z);
        }
      } else if (key == "CELLS") {
        const long long a = s_.integer("the number of cells"), b = s_.integer("the size");
        check_count(s_, a, 2, "cells");
        check_count(s_, b, 2, "cell indices");
        v5_ ? cells5(a, b, corners, where) : cells4(a, b, corners, where);
      } else if (key == "CELL_TYPES") {
        const long long n = s_.integer("the number of cell types");
        if (n != static_cast<long long>(corners.size()))
          s_.fail_at(at, "CELL_TYPES has " + std::to_string(n) + " entries for " +
                             std::to_string(corners.size()) + " cells");
        for (long long k = 0; k < n; ++k) {
          const long long w = s_.mark();
          MeshCell c;
          c.shape = vtk_shape(s_, s_.integer("a cell type"), w);
          c.corners = std::move(corners[size_t(k)]);
          c.where = where[size_t(k)];
          int vtk = 1;  // VTK's orientation; a tetrahedron against it is counted
          if (const auto why = accept_cell(mesh_, c, vtk)) s_.fail_at(c.where, *why);
          mesh_.cells.push_back(std::move(c));
        }
      } else if (key == "CELL_DATA" || key == "POINT_DATA") {
        const long long n = s_.integer("the number of values");
        const long long expected = key == "CELL_DATA"
                                       ? static_cast<long long>(mesh_.cells.size())
                                       : static_cast<long long>(mesh_.vertices.size());
        if (n != expected)
          s_.fail_at(at,
                     key + " has " + std::to_string(n) + " values for " + std::to_string(expected));
        cell_data_ = key == "CELL_DATA";
        count_ = n;
      } else if (key == "SCALARS") {
        const std::string name = s_.word("the array name");
        s_.word("the data type");
        std::string line = s_.rest_of_line();
        const long long comps = line.find_first_not_of(" \t\r") == std::string::npos
                                    ? 1
                                    : std::strtoll(line.c_str(), nullptr, 10);
        if (comps < 1 || comps > 4) s_.fail_at(at, "SCALARS must have 1 to 4 components");
        if (s_.word("LOOKUP_TABLE") != "LOOKUP_TABLE")
          s_.fail("expected LOOKUP_TABLE after SCALARS");
        s_.word("the lookup table name");
        array(name, comps, count_, at);
      } else if (key == "FIELD") {
        s_.word("the field name");
        const long long arrays = s_.integer_in("the number of arrays", 0, 10000);
        for (long long k = 0; k < arrays; ++k) {
          const long long w = s_.mark();
          const std::string name = s_.word("the array name");
          const long long comps = s_.integer_in("the number of components", 1, 1000);
          const long long tuples = s_.integer("the number of tuples");
          s_.word("the data type");
          array(name, comps, tuples, w);
        }
      } else if (key == "VECTORS" || key == "NORMALS" || key == "TENSORS") {
        s_.word("the array name");
        s_.word("the data type");
        array("", key == "TENSORS" ? 9 : 3, count_, at);
      } else if (key == "METADATA") {  // information lines up to a blank line
        s_.rest_of_line();
        while (s_.remaining() &&
               s_.rest_of_line().find_first_not_of(" \t\r") != std::string::npos) {
        }
      } else {
        s_.fail_at(at, "unsupported VTK section '" + key.substr(0, 40) + "'");
      }
    }
    if (mesh_.cells.size() != corners.size()) s_.fail("CELLS without CELL_TYPES");
    if (!wanted_.empty() && !found_) s_.fail("no cell array named '" + wanted_ + "'");
    check_mesh(mesh_,
               [&](const MeshCell& c) { return s_.location(c.where ? c.where : s_.where()); });
    return std::move(mesh_);
  }

 private:
  /// Legacy CELLS: per cell its corner count then the corners.
  void cells4(long long n, long long size, std::vector<std::vector<int>>& out,
              std::vector<long long>& where) {
    long long used = 0;
    for (long long k = 0; k < n; ++k) {
      where.push_back(s_.mark());
      const long long c = s_.integer_in("a cell's node count", 1, 1000);
      used += c + 1;
      if (used > size)
        s_.fail("the cells hold more indices than the CELLS size " + std::to_string(size));
      out.push_back(read_indices(c));
    }
    if (used != size)
      s_.fail("the cells hold " + std::to_string(used) + " indices, the CELLS size says " +
              std::to_string(size));
  }

  /// Version 5.1 CELLS: OFFSETS (n values, from 0) then CONNECTIVITY (size values).
  void cells5(long long offsets, long long size, std::vector<std::vector<int>>& out,
              std::vector<long long>& where) {
    if (offsets < 1) s_.fail("CELLS needs at least one offset");
    if (s_.word("OFFSETS") != "OFFSETS") s_.fail("expected OFFSETS");
    s_.word("the offset type");
    std::vector<long long> off;
    for (long long k = 0; k < offsets; ++k) {
      off.push_back(s_.integer("an offset"));
      if ((k == 0 && off[0] != 0) || (k > 0 && (off[size_t(k)] <= off[size_t(k) - 1] ||
                                                off[size_t(k)] - off[size_t(k) - 1] > 1000)))
        s_.fail("offsets must start at 0 and increase");
    }
    if (off.back() != size)
      s_.fail("the last offset must be the connectivity size " + std::to_string(size));
    if (s_.word("CONNECTIVITY") != "CONNECTIVITY") s_.fail("expected CONNECTIVITY");
    s_.word("the connectivity type");
    for (size_t k = 0; k + 1 < off.size(); ++k) {
      where.push_back(s_.mark());
      out.push_back(read_indices(off[k + 1] - off[k]));
    }
  }

  std::vector<int> read_indices(long long count) {
    std::vector<int> c;
    for (long long i = 0; i < count; ++i)
      c.push_back(static_cast<int>(
          s_.integer_in("a point index", 0, static_cast<long long>(mesh_.vertices.size()) - 1)));
    return c;
  }

  /// Reads comps x tuples values; a cell array of one component is the region tags when it
  /// is the one asked for (or the first, when none is named).
  void array(const std::string& name, long long comps, long long tuples, long long at) {
    check_count(s_, tuples, 2, "array tuples");  // first: comps * tuples must not overflow
    check_count(s_, comps * tuples, 2, "array values");
    const bool tags = cell_data_ && comps == 1 && !found_ && !name.empty() &&
                      (wanted_.empty() || wanted_ == name) &&
                      tuples == static_cast<long long>(mesh_.cells.size());
    if (cell_data_ && !found_ && wanted_ == name && !tags)
      s_.fail_at(at, "the cell array '" + name + "' must have one component per cell");
    for (long long k = 0; k < comps * tuples; ++k) {
      const double v = s_.number("an array value");
      if (!tags) continue;
      if (v != std::floor(v) || std::abs(v) > 2e9)
        s_.fail("the region array '" + name + "' must hold integers (found " + std::to_string(v) +
                ")");
      mesh_.cells[size_t(k)].region = static_cast<int>(v);
    }
    found_ = found_ || tags;
  }

  MeshScan s_;
  CellMesh mesh_;
  std::string wanted_;
  bool v5_ = false, cell_data_ = false, found_ = false;
  long long count_ = 0;
};

}  // namespace

CellMesh parse_vtk(const char* data, size_t size, const std::string& name,
                   const std::string& region_array) {
  return VtkReader(data, size, name, region_array).read();
}

}  // namespace dampbound
