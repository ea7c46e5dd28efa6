// Mesh files by format: the extension (or the scene's `format` key) picks the reader.
#include <cctype>
#include <fstream>

#include "core/io/files.hpp"
#include "core/io/mesh_file.hpp"
#include "core/io/mesh_msh.hpp"
#include "core/io/mesh_obj.hpp"
#include "core/io/mesh_tetgen.hpp"
#include "core/io/mesh_vtk.hpp"
#include "core/io/scene_text.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {

std::string extension(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

/// The file's text, or "" when `optional` and it does not exist.
std::string text_of(const std::string& path, bool optional = false) {
  if (optional && !std::ifstream(path)) return "";
  try {
    return read_file_text(path, kMaxMeshBytes);
  } catch (const std::exception& e) {
    throw InputError("cannot read the mesh file: " + std::string(e.what()));
  }
}

}  // namespace

std::optional<std::string> mesh_format(const std::string& path, const std::string& format) {
  const std::string key = format.empty() ? extension(path) : format;
  if (key == "obj" || key == "msh" || key == "vtk") return key;
  if (key == "tetgen" || key == "node" || key == "ele") return "tetgen";
  return std::nullopt;
}

CellMesh read_mesh_file(const std::string& path, const std::string& format,
                        const std::string& region_array) {
  const std::optional<std::string> f = mesh_format(path, format);
  if (f == "obj") {
    const std::string text = text_of(path);
    return cells_from_obj(parse_obj(text, path));
  }
  if (f == "msh" || f == "vtk") {
    const std::string text = text_of(path);
    return f == "msh" ? parse_msh(text.data(), text.size(), path)
                      : parse_vtk(text.data(), text.size(), path, region_array);
  }
  if (f == "tetgen") {
    const auto dot = path.find_last_of('.');
    const std::string stem = extension(path).empty() ? path : path.substr(0, dot);
    const std::string node = stem + ".node", ele = stem + ".ele", face = stem + ".face";
    return parse_tetgen(text_of(node), node, text_of(ele), ele, text_of(face, true), face);
  }
  throw InputError(path +
                   ": unknown mesh format (use .obj, .msh, .node/.ele or .vtk, or set "
                   "format = \"obj\", \"msh\", \"tetgen\" or \"vtk\")");
}

}  // namespace dampbound
