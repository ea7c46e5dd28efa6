// Gmsh MSH 2.2 and 4.1 readers, ASCII and binary (the format as documented in the Gmsh
// reference manual, section "MSH file format"). Binary data is little-endian with 8-byte
// doubles and, in 4.1, 8-byte size_t.
#include <cstdint>
#include <map>
#include <unordered_map>
#include <utility>

#include "core/io/detail/mesh_scan.hpp"
#include "core/io/mesh_msh.hpp"

namespace dampbound {
namespace {

/// The shape of a Gmsh element type, or fails naming the type.
CellShape gmsh_shape(MeshScan& s, long long type, long long where) {
  switch (type) {
    case 15:
      return CellShape::point;
    case 1:
      return CellShape::line;
    case 2:
      return CellShape::triangle;
    case 3:
      return CellShape::quad;
    case 4:
      return CellShape::tetra;
    default:
      break;
  }
  static const std::map<long long, const char*> known = {{5, "hexahedron"},
                                                         {6, "prism"},
                                                         {7, "pyramid"},
                                                         {8, "second-order line"},
                                                         {9, "6-node triangle"},
                                                         {10, "9-node quadrangle"},
                                                         {11, "10-node tetrahedron"},
                                                         {16, "8-node quadrangle"}};
  const auto it = known.find(type);
  s.fail_at(where, "unsupported element type " + std::to_string(type) +
                       (it != known.end() ? std::string(" (") + it->second + ")" : "") +
                       ": only points, lines, triangles, quadrangles and tetrahedra are read");
}


class MshReader {
 public:
  MshReader(const char* data, size_t size, const std::string& name) : s_(data, size, name) {}

  CellMesh read() {
    if (s_.at_end() || s_.word("$MeshFormat") != "$MeshFormat")
      s_.fail("not a Gmsh MSH file (it does not start with $MeshFormat)");
    const std::string version = s_.word("the version");
    if (version == "2.2" || version == "2.1" || version == "2") {
      v4_ = false;
    } else if (version == "4.1") {
      v4_ = true;
    } else {
      s_.fail("MSH version " + version.substr(0, 20) + " is not supported (2.2 or 4.1)");
    }
    binary_ = s_.integer_in("the file type", 0, 1) == 1;
    if (s_.integer("the data size") != 8) s_.fail("the data size must be 8");
    if (binary_) {
      s_.skip_newline();
      s_.set_binary(true);
      if (s_.binary<std::int32_t>("the endianness check") != 1)
        s_.fail("the endianness check is not 1: a big-endian file is not supported");
    }
    end_section("$EndMeshFormat");
    while (!s_.at_end()) {
      const long long at = s_.mark();
      const std::string section = s_.word("a section");
      if (section == "$PhysicalNames") {
        physical_names();
      } else if (section == "$Entities" && v4_) {
        entities();
      } else if (section == "$Nodes") {
        v4_ ? nodes4() : nodes2();
      } else if (section == "$Elements") {
        if (!have_nodes_) s_.fail_at(at, "$Elements before $Nodes");
        v4_ ? elements4() : elements2();
      } else if (section.size() > 1 && section[0] == '$') {
        s_.skip_past("$End" + section.substr(1));  // a section this tool does not use
        continue;
      } else {
        s_.fail_at(at, "expected a $Section, found '" + section.substr(0, 40) + "'");
      }
    }
    if (!have_nodes_) s_.fail("the file has no $Nodes section");
    check_mesh(mesh_,
               [&](const MeshCell& c) { return s_.location(c.where ? c.where : s_.where()); });
    return std::move(mesh_);
  }

 private:
  void end_section(const char* marker) {
    if (binary_) s_.skip_newline();
    if (s_.word(marker) != marker) s_.fail(std::string("expected ") + marker);
  }
  long long count(const char* what, size_t min_bytes) {
    const long long n =
        binary_ && v4_ ? static_cast<long long>(s_.binary<std::uint64_t>(what)) : s_.integer(what);
    check_count(s_, n, min_bytes, what);
    return n;
  }
  int int32(const char* what) {
    return binary_ ? s_.binary<std::int32_t>(what) : int(s_.integer_in(what, INT32_MIN, INT32_MAX));
  }
  long long tag(const char* what) {  // size_t in 4.1 binary, int in 2.2 binary
    if (!binary_) return s_.integer(what);
    return v4_ ? static_cast<long long>(s_.binary<std::uint64_t>(what))
               : s_.binary<std::int32_t>(what);
  }
  double real(const char* what) { return binary_ ? s_.binary<double>(what) : s_.number(what); }

  void physical_names() {
    // Always ASCII, also in binary files: `dim tag "name"` per line.
    if (binary_) s_.skip_newline();
    const long long n = s_.integer("the number of physical names");
    check_count(s_, n, 4, "physical names");
    for (long long k = 0; k < n; ++k) {
      s_.integer("a physical dimension");
      const int t = int(s_.integer_in("a physical tag", INT32_MIN, INT32_MAX));
      std::string rest = s_.rest_of_line();
      const auto a = rest.find('"'), b = rest.rfind('"');
      if (a == std::string::npos || b == a) s_.fail("a physical name must be quoted");
      mesh_.region_names[rest.substr(a + 1, b - a - 1)] = t;
    }
    if (s_.word("$EndPhysicalNames") != "$EndPhysicalNames") s_.fail("expected $EndPhysicalNames");
  }

  void entities() {
    if (binary_) s_.skip_newline();
    long long n[4];
    for (long long& c : n) c = count("an entity count", 8);
    for (int dim = 0; dim < 4; ++dim)
      for (long long k = 0; k < n[dim]; ++k) {
        const int t = int32("an entity tag");
        for (int c = 0; c < (dim == 0 ? 3 : 6); ++c) real("an entity bound");
        const long long np = count("physical tags", 4);
        int first = 0;
        for (long long p = 0; p < np; ++p) {
          const int pt = int32("a physical tag");
          if (p == 0) first = pt;
        }
        physical_[{dim, t}] = first;
        if (dim > 0) {
          const long long nb = count("bounding entities", 4);
          for (long long b = 0; b < nb; ++b) int32("a bounding entity");
        }
      }
    end_section("$EndEntities");
  }

  void add_vertex(long long id, const Vec3& x, long long at) {
    if (!ids_.emplace(id, int(mesh_.vertices.size())).second)
      s_.fail_at(at, "node tag " + std::to_string(id) + " appears twice");
    mesh_.vertices.push_back(x);
  }

  void nodes2() {
    const long long n = s_.integer("the number of nodes");
    check_count(s_, n, binary_ ? 28 : 8, "nodes");
    if (binary_) s_.skip_newline();
    for (long long k = 0; k < n; ++k) {
      const long long at = s_.mark();
      const long long id = tag("a node tag");
      const double x = real("x"), y = real("y"), z = real("z");
      add_vertex(id, {x, y, z}, at);
    }
    end_section("$EndNodes");
    have_nodes_ = true;
  }

  void nodes4() {
    if (binary_) s_.skip_newline();
    const long long blocks = count("the number of node blocks", 8);
    count("the number of nodes", 0);
    tag("the minimum node tag");
    tag("the maximum node tag");
    for (long long b = 0; b < blocks; ++b) {
      const long long at = s_.mark();
      int32("an entity dimension");
      int32("an entity tag");
      if (int32("the parametric flag") != 0) s_.fail_at(at, "parametric nodes are not supported");
      const long long n = count("nodes in a block", binary_ ? 32 : 8);
      std::vector<std::pair<long long, long long>> tags;  // (tag, where)
      for (long long k = 0; k < n; ++k) {
        const long long w = s_.mark();
        tags.emplace_back(tag("a node tag"), w);
      }
      for (const auto& [id, w] : tags) {
        const double x = real("x"), y = real("y"), z = real("z");
        add_vertex(id, {x, y, z}, w);
      }
    }
    end_section("$EndNodes");
    have_nodes_ = true;
  }

  /// One element's node tags as vertex indices, validated; a tetrahedron against Gmsh's
  /// orientation (+1) is counted.
  void add_cell(CellShape shape, const std::vector<long long>& node_tags, int region,
                long long at) {
    MeshCell c;
    c.shape = shape;
    c.region = region;
    c.where = at;
    for (long long t : node_tags) {
      const auto it = ids_.find(t);
      if (it == ids_.end())
        s_.fail_at(at, "the element refers to node tag " + std::to_string(t) +
                           ", which $Nodes does not define");
      c.corners.push_back(it->second);
    }
    int gmsh = 1;
    if (const auto why = accept_cell(mesh_, c, gmsh)) s_.fail_at(at, *why);
    mesh_.cells.push_back(std::move(c));
  }

  void elements2() {
    const long long n = s_.integer("the number of elements");
    check_count(s_, n, binary_ ? 12 : 6, "elements");
    if (binary_) s_.skip_newline();
    for (long long k = 0; k < n;) {
      const long long at = s_.mark();
      if (!binary_) {  // id type ntags tags... nodes...
        s_.integer("an element tag");
        const long long type = s_.integer("an element type");
        const CellShape shape = gmsh_shape(s_, type, at);
        const long long ntags = s_.integer_in("the number of tags", 0, 64);
        int region = 0;
        for (long long t = 0; t < ntags; ++t) {
          const int v = int(s_.integer_in("a tag", INT32_MIN, INT32_MAX));
          if (t == 0) region = v;
        }
        std::vector<long long> nodes;
        for (int c = 0; c < static_cast<int>(corner_count(shape)); ++c) nodes.push_back(s_.integer("a node tag"));
        add_cell(shape, nodes, region, at);
        ++k;
        continue;
      }
      // Binary: blocks of (type, count, ntags) then count x (id, tags, nodes) as int32.
      const CellShape shape = gmsh_shape(s_, s_.binary<std::int32_t>("an element type"), at);
      const long long follow = s_.binary<std::int32_t>("an element count");
      const long long ntags = s_.binary<std::int32_t>("a tag count");
      if (follow < 1 || follow > n - k || ntags < 0 || ntags > 64)
        s_.fail_at(at, "bad element block header");
      for (long long e = 0; e < follow; ++e, ++k) {
        const long long w = s_.mark();
        s_.binary<std::int32_t>("an element tag");
        int region = 0;
        for (long long t = 0; t < ntags; ++t) {
          const int v = s_.binary<std::int32_t>("a tag");
          if (t == 0) region = v;
        }
        std::vector<long long> nodes;
        for (int c = 0; c < static_cast<int>(corner_count(shape)); ++c)
          nodes.push_back(s_.binary<std::int32_t>("a node tag"));
        add_cell(shape, nodes, region, w);
      }
    }
    end_section("$EndElements");
  }

  void elements4() {
    if (binary_) s_.skip_newline();
    const long long blocks = count("the number of element blocks", 8);
    count("the number of elements", 0);
    tag("the minimum element tag");
    tag("the maximum element tag");
    for (long long b = 0; b < blocks; ++b) {
      const long long at = s_.mark();
      const int dim = int32("an entity dimension");
      const int entity = int32("an entity tag");
      const CellShape shape = gmsh_shape(s_, int32("an element type"), at);
      if (cell_dimension(shape) != dim)
        s_.fail_at(at, std::string("a ") + to_string(shape) + " in an entity of dimension " +
                           std::to_string(dim));
      const long long n = count("elements in a block", binary_ ? 16 : 4);
      const auto ph = physical_.find({dim, entity});
      const int region = ph == physical_.end() ? 0 : ph->second;
      for (long long e = 0; e < n; ++e) {
        const long long w = s_.mark();
        tag("an element tag");
        std::vector<long long> nodes;
        for (int c = 0; c < static_cast<int>(corner_count(shape)); ++c) nodes.push_back(tag("a node tag"));
        add_cell(shape, nodes, region, w);
      }
    }
    end_section("$EndElements");
  }

  MeshScan s_;
  CellMesh mesh_;
  bool v4_ = false, binary_ = false, have_nodes_ = false;
  std::unordered_map<long long, int> ids_;       // node tag -> vertex index
  std::map<std::pair<int, int>, int> physical_;  // (dim, entity tag) -> first physical tag
};

}  // namespace

CellMesh parse_msh(const char* data, size_t size, const std::string& name) {
  return MshReader(data, size, name).read();
}

}  // namespace dampbound
