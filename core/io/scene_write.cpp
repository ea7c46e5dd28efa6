// Scenes written back as TOML (docs/scene-format.md). Keys in the order of the annotated scene
// in docs/guide.md, numbers in their shortest form that reads back to the same double
// (std::to_chars), strings quoted by toml++'s own writer; the reader is core/io/scene_file.cpp.
#include "core/io/scene_write.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <ostream>
#include <sstream>

#include "core/io/files.hpp"
#include "core/io/scene_file.hpp"

namespace dampbound {

namespace {

namespace fs = std::filesystem;

/// One table as "key = value" lines, in the order given.
using Table = std::vector<std::pair<std::string, std::string>>;

/// Decimal text that reads back to exactly `x` (std::to_chars' shortest round trip), always
/// with a '.' or an exponent (TOML's float syntax).
std::string num(double x) {
  // Plain decimals (0.0005) while they stay short, else the shortest form (1.1197e-05).
  char buf[400];
  auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::fixed);
  if (r.ec != std::errc() || r.ptr - buf > 12) r = std::to_chars(buf, buf + sizeof buf, x);
  std::string t(buf, r.ptr);
  if (t.find_first_of(".eEn") == std::string::npos) t += ".0";  // "n": nan/inf never get here
  return t;
}
std::string num(long long x) {
  return std::to_string(x);
}
std::string num(int x) {
  return std::to_string(x);
}
std::string boolean(bool b) {
  return b ? "true" : "false";
}
std::string str(const std::string& s) {
  std::ostringstream o;
  o << toml::value<std::string>(s);
  return o.str();
}
std::string vec3(const Vec3& v) {
  return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]";
}

/// A value of a table copied from a source file (numbers, strings, booleans, arrays of them).
std::string value_text(const toml::node& n) {
  if (const auto* d = n.as_floating_point()) return num(d->get());
  if (const auto* i = n.as_integer()) return num(static_cast<long long>(i->get()));
  if (const auto* b = n.as_boolean()) return boolean(b->get());
  if (const auto* t = n.as_string()) return str(t->get());
  if (const auto* a = n.as_array()) {
    std::string o = "[";
    for (size_t k = 0; k < a->size(); ++k) o += (k ? ", " : "") + value_text(*a->get(k));
    return o + "]";
  }
  std::ostringstream o;  // anything else (an inline table, a date): toml++'s own writer
  n.visit([&o](const auto& v) { o << v; });
  return o.str();
}

Table copy_table(const toml::table& t) {
  Table out;
  for (auto&& [key, value] : t) out.emplace_back(std::string(key.str()), value_text(value));
  return out;
}

void put(std::ostream& out, const Table& t) {
  for (const auto& [key, value] : t) out << key << " = " << value << "\n";
}

/// The parameter keys of [params] and [[run]] (scene_file.cpp's read_params).
void put_params(Table& t, const Params& p) {
  t.emplace_back("m", num(p.m));
  t.emplace_back("kappa", num(p.kappa));
  if (p.zeta)
    t.emplace_back("zeta", num(*p.zeta));
  else
    t.emplace_back("gamma", num(p.gamma));
  t.emplace_back("dt", num(p.dt));
  t.emplace_back("policy", str(to_string(p.policy)));
  t.emplace_back("factor", num(p.factor));
  t.emplace_back("integrator", str(to_string(p.integrator)));
  // SPEC 10's damping, where the scene has it (a file without them reads back as 0).
  if (p.kd != 0) t.emplace_back("kd", num(p.kd));
  if (p.rayleigh_mass != 0) t.emplace_back("rayleigh_mass", num(p.rayleigh_mass));
  if (p.rayleigh_stiffness != 0) t.emplace_back("rayleigh_stiffness", num(p.rayleigh_stiffness));
}

void table_section(std::ostream& out, const char* name, const Table& t) {
  out << "\n[" << name << "]\n";
  put(out, t);
}

void array_section(std::ostream& out, const char* name, const Table& t) {
  out << "\n[[" << name << "]]\n";
  put(out, t);
}

/// The plain grid of the spec, with every scale at its default.
bool is_plain_grid(const SceneSpec& s) {
  return s.grid && same_topology(s.model, make_grid(*s.grid));
}

/// The source file's geometry tables, when they still give this model. Empty otherwise.
std::string source_geometry(const SceneSpec& s, const std::string& dest_path) {
  if (s.path.empty()) return "";
  toml::table root;
  try {
    root = toml::parse(read_file_text(s.path), s.path);
  } catch (const std::exception&) {
    return "";
  }
  std::ostringstream out;
  for (const char* key : {"grid", "mesh"}) {
    const toml::table* t = root[key].as_table();
    if (t == nullptr) continue;
    toml::table copy = *t;
    if (const auto file = copy["file"].value<std::string>(); file && std::string(key) == "mesh") {
      // A mesh path is relative to the scene file: re-anchor it at the new file.
      fs::path mesh = fs::path(*file);
      if (mesh.is_relative()) mesh = fs::absolute(fs::path(s.path).parent_path() / mesh);
      const fs::path dest_dir = fs::absolute(fs::path(dest_path)).parent_path();
      std::error_code ec;
      const fs::path rel = fs::relative(mesh.lexically_normal(), dest_dir, ec);
      copy.insert_or_assign("file", (ec || rel.empty() ? mesh.lexically_normal() : rel).string());
    }
    table_section(out, key, copy_table(copy));
  }
  for (const char* key : {"node", "spring", "region"}) {
    const toml::array* a = root[key].as_array();
    if (a == nullptr) continue;
    for (const toml::node& e : *a)
      if (const toml::table* t = e.as_table()) array_section(out, key, copy_table(*t));
  }
  // Guard: the copied tables must compile to the model the tuner ran (the file may have
  // changed on disk since it was loaded).
  try {
    const SceneSpec back = parse_scene(out.str(), dest_path);
    if (!same_topology(back.model, s.model)) return "";
  } catch (const std::exception&) {
    return "";
  }
  return out.str();
}

/// Every node and spring written out ([[node]] / [[spring]]).
void explicit_geometry(std::ostream& out, const ModelSpec& m) {
  for (int i = 0; i < m.node_count(); ++i) {
    const auto k = static_cast<size_t>(i);
    Table t{{"x", vec3(m.rest[k])}};
    if (m.fixed[k]) t.emplace_back("fixed", "true");
    if (m.mass_scale[k] != 1) t.emplace_back("mass_scale", num(m.mass_scale[k]));
    if (m.gamma_scale[k] != 1) t.emplace_back("gamma_scale", num(m.gamma_scale[k]));
    if (m.anchor_scale[k] != 0) t.emplace_back("anchor_scale", num(m.anchor_scale[k]));
    if (!m.external_force[k].isZero(0)) t.emplace_back("force", vec3(m.external_force[k]));
    array_section(out, "node", t);
  }
  for (const Spring& sp : m.springs) {
    Table t{{"nodes", "[" + num(sp.i) + ", " + num(sp.j) + "]"},
            {"rest_length", num(sp.rest_length)}};
    if (sp.kappa_scale != 1) t.emplace_back("kappa_scale", num(sp.kappa_scale));
    if (sp.kd_scale != 1) t.emplace_back("kd_scale", num(sp.kd_scale));
    array_section(out, "spring", t);
  }
  // An anchor's own dashpot scale has no [[node]] key: a [[region]] around the node alone
  // sets it (and the kd_scale of a spring between two nodes at that very point, which the
  // [[spring]] above gives the same way).
  for (size_t k = 0; k < m.anchor_kd_scale.size(); ++k)
    if (m.anchor_kd_scale[k] != 1)
      array_section(out, "region",
                    {{"min", vec3(m.rest[k])}, {"max", vec3(m.rest[k])},
                     {"kd_scale", num(m.anchor_kd_scale[k])}});
}

void write_geometry(std::ostream& out, const SceneSpec& s, const std::string& dest_path) {
  if (is_plain_grid(s)) {
    table_section(out, "grid",
                  {{"nx", num(s.grid->nx)},
                   {"nz", num(s.grid->nz)},
                   {"spacing", num(s.grid->spacing)},
                   {"diagonals", boolean(s.grid->diagonals)},
                   {"anchors", boolean(s.grid->anchors)}});
    return;
  }
  const std::string copied = source_geometry(s, dest_path);
  if (!copied.empty()) {
    out << copied;
    return;
  }
  explicit_geometry(out, s.model);
}

Table expect_table(const Expectation& e) {
  Table t;
  auto range = [&t](const char* key, const std::optional<int>& lo, const std::optional<int>& hi) {
    if (lo && hi) t.emplace_back(key, "[" + num(*lo) + ", " + num(*hi) + "]");
  };
  if (!e.run.empty()) t.emplace_back("run", str(e.run));
  t.emplace_back("rule", str(to_string(e.rule)));  // explicit: the file keeps its meaning
  if (e.outcome) t.emplace_back("outcome", str(to_string(*e.outcome)));
  range("iterations", e.iterations_min, e.iterations_max);
  range("first_entry", e.first_entry_min, e.first_entry_max);
  if (e.left) t.emplace_back("left", boolean(*e.left));
  range("left_at", e.left_at_min, e.left_at_max);
  range("settled_at", e.settled_at_min, e.settled_at_max);
  if (e.max_displacement_below)
    t.emplace_back("max_displacement_below", num(*e.max_displacement_below));
  if (e.unstabilisable_max) t.emplace_back("unstabilisable_max", num(*e.unstabilisable_max));
  if (e.violations_max) t.emplace_back("violations_max", num(*e.violations_max));
  if (e.violations_min) t.emplace_back("violations_min", num(*e.violations_min));
  if (e.mass_scale_dt) t.emplace_back("mass_scale_dt", num(*e.mass_scale_dt));
  if (e.added_mass_min)
    t.emplace_back("added_mass_percent",
                   "[" + num(*e.added_mass_min) + ", " + num(*e.added_mass_max) + "]");
  range("scaled_nodes", e.scaled_nodes_min, e.scaled_nodes_max);
  return t;
}

}  // namespace

bool same_topology(const ModelSpec& a, const ModelSpec& b) {
  if (a.rest != b.rest || a.mass_scale != b.mass_scale || a.gamma_scale != b.gamma_scale ||
      a.anchor_scale != b.anchor_scale || a.external_force != b.external_force ||
      a.fixed != b.fixed || a.springs.size() != b.springs.size())
    return false;
  for (size_t k = 0; k < a.springs.size(); ++k) {
    const Spring &x = a.springs[k], &y = b.springs[k];
    if (x.i != y.i || x.j != y.j || x.rest_length != y.rest_length ||
        x.kappa_scale != y.kappa_scale)
      return false;
  }
  return true;
}

Expectation expectation_for(const RunResult& r, const std::string& run,
                            const ExpectTolerance& tol, StopRule rule) {
  Expectation e;
  e.run = run;
  e.rule = rule;
  e.outcome = r.outcome;
  auto range = [&tol](int value, std::optional<int>& lo, std::optional<int>& hi) {
    const int k = std::max(
        std::max(0, tol.iterations),
        static_cast<int>(std::ceil(std::max(0.0, tol.iteration_fraction) * value)));
    lo = std::max(1, value - k);
    hi = value + k;
  };
  // At the limit (not restored; settled, not settled) the iteration says nothing new.
  if (r.outcome == Outcome::restored || r.outcome == Outcome::diverged)
    range(r.iterations, e.iterations_min, e.iterations_max);
  if (rule == StopRule::settled) {
    if (r.first_entry > 0) range(r.first_entry, e.first_entry_min, e.first_entry_max);
    if (r.outcome != Outcome::diverged) {
      e.left = r.left_at > 0;
      if (r.left_at > 0) range(r.left_at, e.left_at_min, e.left_at_max);
    }
    if (r.outcome == Outcome::settled) range(r.settled_at, e.settled_at_min, e.settled_at_max);
  }
  if (r.outcome != Outcome::diverged && tol.displacement_factor > 1 &&
      std::isfinite(r.max_displacement) && r.max_displacement > 0)
    e.max_displacement_below = r.max_displacement * tol.displacement_factor;
  if (tol.counts) {
    e.violations_max = r.violations;
    e.unstabilisable_max = r.unstabilisable;
  }
  return e;
}

void write_scene_toml(std::ostream& out, const SceneSpec& s, const std::string& dest_path,
                      const std::vector<std::string>& header) {
  for (const std::string& line : header) out << "# " << line << "\n";
  Table top;
  if (!s.name.empty()) top.emplace_back("name", str(s.name));
  if (!s.description.empty()) top.emplace_back("description", str(s.description));
  top.emplace_back("watch", num(s.watched));
  put(out, top);
  write_geometry(out, s, dest_path);
  Table params;
  put_params(params, s.params);
  table_section(out, "params", params);
  for (const Perturbation& p : s.perturbations)
    array_section(out, "perturb",
                  {{"node", num(p.node)},
                   {"displacement", vec3(p.displacement)},
                   {"velocity", vec3(p.velocity)}});
  table_section(out, "protocol",
                {{"max_iterations", num(s.rules.max_iterations)},
                 {"restore_fraction", num(s.rules.restore_fraction)},
                 {"diverge_factor", num(s.rules.diverge_factor)},
                 {"reference", num(s.rules.reference)}});
  for (const CutEvent& c : s.cuts)
    array_section(out, "cut",
                  {{"iteration", num(c.iteration)},
                   {"from", "[" + num(c.from[0]) + ", " + num(c.from[1]) + "]"},
                   {"to", "[" + num(c.to[0]) + ", " + num(c.to[1]) + "]"}});
  for (const RunSpec& r : s.runs) {
    Table t{{"label", str(r.label)}};
    put_params(t, r.params);
    t.emplace_back("max_iterations", num(r.rules.max_iterations));
    array_section(out, "run", t);
  }
  for (const Expectation& e : s.expectations) array_section(out, "expect", expect_table(e));
}

std::string scene_toml(const SceneSpec& scene, const std::string& dest_path,
                       const std::vector<std::string>& header) {
  std::ostringstream out;
  write_scene_toml(out, scene, dest_path, header);
  return out.str();
}

}  // namespace dampbound
