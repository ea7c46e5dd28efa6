#include "core/io/mesh_obj.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <utility>

#include "core/io/detail/mesh_scan.hpp"
#include "core/io/format.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

namespace {

[[noreturn]] void fail(const std::string& path, int line, const std::string& msg) {
  throw InputError(path + ":" + std::to_string(line) + ": " + msg);
}

/// A token of the file as a message quotes it: at most 24 characters, control characters
/// escaped (the file may be anything a scene named).
std::string quoted(const std::string& token) {
  return "'" + printable(token.size() > 24 ? token.substr(0, 24) + "..." : token) + "'";
}

/// A finite number, or a failure naming the line.
double read_number(const std::string& token, const std::string& path, int line) {
  const std::optional<double> x = finite_number(token);
  if (!x) fail(path, line, quoted(token) + " is not a finite number");
  return *x;
}

/// The vertex index of a face corner "i", "i/t", "i//n" or "i/t/n" (1-based, or negative
/// counting back), as a 0-based index into the `count` vertices read so far.
int read_corner(const std::string& token, int count, const std::string& path, int line) {
  const std::string head = token.substr(0, token.find('/'));
  errno = 0;
  char* end = nullptr;
  const long k = std::strtol(head.c_str(), &end, 10);
  if (head.empty() || end != head.c_str() + head.size() || errno == ERANGE)  // a NUL: no end
    fail(path, line, "face corner " + quoted(token) + " has no vertex index");
  const long index = k > 0 ? k - 1 : count + k;
  if (k == 0 || index < 0 || index >= count)
    fail(path, line,
         "face corner " + quoted(token) + " refers to a vertex that does not exist (" +
             std::to_string(count) + " so far)");
  return static_cast<int>(index);
}

}  // namespace

ObjMesh parse_obj(const std::string& text, const std::string& path) {
  ObjMesh mesh;
  std::istringstream in(text);
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    const std::string content = raw.substr(0, raw.find('#'));
    std::istringstream ls(content);
    std::string keyword;
    if (!(ls >> keyword)) continue;
    std::vector<std::string> args;
    for (std::string a; ls >> a;) args.push_back(a);
    if (keyword == "v") {
      if (args.size() < 3 || args.size() > 4)
        fail(path, line, "a vertex needs 3 coordinates (v x y z)");
      mesh.vertices.emplace_back(read_number(args[0], path, line), read_number(args[1], path, line),
                                 read_number(args[2], path, line));
    } else if (keyword == "f") {
      if (args.size() < 3) fail(path, line, "a face needs at least 3 corners");
      std::vector<int> face;
      const int count = static_cast<int>(mesh.vertices.size());
      for (const std::string& a : args) face.push_back(read_corner(a, count, path, line));
      std::vector<int> sorted = face;
      std::sort(sorted.begin(), sorted.end());
      if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
        fail(path, line, "a face uses the same vertex twice");
      mesh.faces.push_back(std::move(face));
    }
    // vt, vn, vp, g, o, s, l, usemtl, mtllib ...: not part of the spring model.
  }
  if (mesh.faces.empty()) fail(path, std::max(line, 1), "the mesh has no face (f ...)");
  return mesh;
}

CellMesh cells_from_obj(const ObjMesh& mesh) {
  CellMesh out;
  out.vertices = mesh.vertices;
  for (const std::vector<int>& f : mesh.faces) {
    MeshCell c;
    c.shape = f.size() == 3 ? CellShape::triangle : f.size() == 4 ? CellShape::quad
                                                                  : CellShape::polygon;
    c.corners = f;
    c.where = static_cast<long long>(out.cells.size());
    out.cells.push_back(std::move(c));
  }
  return out;
}

ModelSpec model_from_obj(const ObjMesh& mesh, const MeshSprings& how) {
  return model_from_mesh(cells_from_obj(mesh), how);
}

}  // namespace dampbound
