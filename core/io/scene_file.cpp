// The TOML scene format (docs/scene-format.md): parsing and validation with file:line errors.
#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>

#include "core/io/detail/scene_expect.hpp"
#include "core/io/detail/scene_mesh.hpp"
#include "core/io/detail/scene_reader.hpp"
#include "core/io/files.hpp"
#include "core/io/scene_file.hpp"
#include "core/io/scene_text.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {
namespace {

using scene_file::Reader;

/// Reads the parameter keys (m, kappa, gamma or zeta, dt, policy, factor, integrator, and
/// SPEC 10's kd, rayleigh_mass, rayleigh_stiffness) present in `t` into `p`. gamma and zeta
/// exclude each other; either one replaces the other inherited.
void read_params(const Reader& r, const toml::table& t, const std::string& table, Params& p) {
  if (auto* n = t.get("m")) p.m = r.positive(*n, "m");
  if (auto* n = t.get("kappa")) p.kappa = r.positive(*n, "kappa");
  if (t.get("gamma") && t.get("zeta"))
    r.fail(*t.get("zeta"), table + ": zeta and gamma exclude each other (zeta: the damping ratio, "
                           "gamma = zeta * 2 sqrt(m_i kappa_i)); give one");
  if (auto* n = t.get("gamma")) {
    p.gamma = r.non_negative(*n, "gamma");
    p.zeta.reset();
  }
  if (auto* n = t.get("zeta")) p.zeta = r.non_negative(*n, "zeta");
  if (auto* n = t.get("dt")) p.dt = r.positive(*n, "dt");
  if (auto* n = t.get("factor")) p.factor = r.non_negative(*n, "factor");
  if (auto* n = t.get("kd")) p.kd = r.non_negative(*n, "kd");
  if (auto* n = t.get("rayleigh_mass")) p.rayleigh_mass = r.non_negative(*n, "rayleigh_mass");
  if (auto* n = t.get("rayleigh_stiffness"))
    p.rayleigh_stiffness = r.non_negative(*n, "rayleigh_stiffness");
  if (auto* n = t.get("policy")) {
    auto pol = parse_policy(r.string(*n, "policy"));
    if (!pol) r.fail(*n, "policy must be one of " + one_of(policy_names()));
    p.policy = *pol;
  }
  if (auto* n = t.get("integrator")) {
    auto in = parse_integrator(r.string(*n, "integrator"));
    if (!in)
      r.fail(*n, "integrator must be one of " + one_of(integrator_names()));
    p.integrator = *in;
  }
}

int read_max_iterations(const Reader& r, const toml::node& n) {
  const long long k = r.integer(n, "max_iterations");
  if (k < 1 || k > 100000000) r.fail(n, "max_iterations must be in 1..100000000");
  return static_cast<int>(k);
}

/// A node reference: an index, or [a, b] on a grid scene.
int node_ref(const Reader& r, const SceneSpec& s, const toml::node& n, const std::string& what) {
  long long index = -1;
  if (n.is_integer()) {
    index = *n.value<long long>();
  } else if (const toml::array* a = n.as_array(); a && a->size() == 2) {
    if (!s.grid) r.fail(n, what + " as [a, b] needs a [grid] geometry");
    const long long ga = r.integer(*a->get(0), what), gb = r.integer(*a->get(1), what);
    if (ga < 0 || ga >= s.grid->nx || gb < 0 || gb >= s.grid->nz)
      r.fail(n, what + " [" + std::to_string(ga) + ", " + std::to_string(gb) + "] is outside the " +
                    std::to_string(s.grid->nx) + " x " + std::to_string(s.grid->nz) + " grid");
    index = ga * s.grid->nz + gb;
  } else {
    r.fail(n, what + " must be a node index or [a, b]");
  }
  if (index < 0 || index >= s.model.node_count())
    r.fail(n, what + " " + std::to_string(index) + " does not exist (the scene has " +
                  std::to_string(s.model.node_count()) + " nodes)");
  return static_cast<int>(index);
}

void read_geometry(const Reader& r, const toml::table& root, SceneSpec& s) {
  const bool has_grid = root.contains("grid");
  const bool has_nodes = root.contains("node");
  const bool has_mesh = root.contains("mesh");
  if (has_grid + has_nodes + has_mesh != 1)
    r.fail(1, has_grid || has_nodes || has_mesh
                  ? "a scene has one geometry: [grid], [[node]] or [mesh], not several"
                  : "the scene has no geometry: add [grid], [[node]] entries or [mesh]");
  if (root.contains("mesh_region") && !has_mesh)
    r.fail(*root.get("mesh_region"), "[[mesh_region]] needs a [mesh] geometry");
  if (has_mesh) {
    scene_file::read_mesh(r, root, s);  // any mesh format, and its [[mesh_region]] tables
    if (root.contains("spring")) r.fail(*root.get("spring"), "[[spring]] needs [[node]] geometry");
    return;
  }
  if (has_grid) {
    const toml::table& g = r.table(*root.get("grid"), "grid");
    r.check_keys(g, "[grid]");
    GridSpec grid;
    const auto nx = r.integer(r.required(g, "nx", "[grid]"), "nx");
    const auto nz = r.integer(r.required(g, "nz", "[grid]"), "nz");
    // Each side first: nx * nz of two huge sides overflows before it is compared.
    if (nx < 1 || nz < 1 || nx > 4000000 || nz > 4000000 || nx * nz > 4000000)
      r.fail(g, "grid size must be 1..4e6 nodes");
    grid.nx = static_cast<int>(nx);
    grid.nz = static_cast<int>(nz);
    grid.spacing = r.positive(r.required(g, "spacing", "[grid]"), "spacing");
    if (auto* n = g.get("diagonals")) grid.diagonals = r.boolean(*n, "diagonals");
    if (auto* n = g.get("anchors")) grid.anchors = r.boolean(*n, "anchors");
    s.grid = grid;
    s.model = make_grid(grid);
    if (root.contains("spring")) r.fail(*root.get("spring"), "[[spring]] needs [[node]] geometry");
    return;
  }
  for (const toml::table& t : r.tables(root, "node")) {
    const int i = add_node(s.model, r.vec3(r.required(t, "x", "[[node]]"), "x"));
    const auto k = static_cast<size_t>(i);
    if (auto* n = t.get("fixed")) s.model.fixed[k] = r.boolean(*n, "fixed");
    if (auto* n = t.get("mass_scale")) s.model.mass_scale[k] = r.positive(*n, "mass_scale");
    if (auto* n = t.get("gamma_scale")) s.model.gamma_scale[k] = r.non_negative(*n, "gamma_scale");
    if (auto* n = t.get("anchor_scale"))
      s.model.anchor_scale[k] = r.non_negative(*n, "anchor_scale");
    if (auto* n = t.get("force")) s.model.external_force[k] = r.vec3(*n, "force");
  }
  // An empty model has no node to watch or perturb, and step() needs one.
  if (s.model.node_count() == 0) r.fail(*root.get("node"), "the scene has no node");
  std::set<std::pair<int, int>> seen;
  for (const toml::table& t : r.tables(root, "spring")) {
    const toml::node& nn = r.required(t, "nodes", "[[spring]]");
    const toml::array* ends = nn.as_array();
    if (!ends || ends->size() != 2) r.fail(nn, "nodes must be [i, j]");
    const int i = node_ref(r, s, *ends->get(0), "spring node");
    const int j = node_ref(r, s, *ends->get(1), "spring node");
    if (i == j) r.fail(nn, "a spring needs two different nodes (got " + std::to_string(i) + ")");
    if (!seen.insert({std::min(i, j), std::max(i, j)}).second)
      r.fail(nn, "duplicate spring " + std::to_string(i) + "-" + std::to_string(j));
    double ks = 1;
    if (auto* n = t.get("kappa_scale")) ks = r.positive(*n, "kappa_scale");
    add_spring(s.model, i, j, ks);
    if (auto* n = t.get("rest_length"))
      s.model.springs.back().rest_length = r.non_negative(*n, "rest_length");
    if (auto* n = t.get("kd_scale")) s.model.springs.back().kd_scale = r.non_negative(*n, "kd_scale");
  }
}

/// [[region]]: scales for the nodes (and springs with both ends) inside a box of rest space.
void read_regions(const Reader& r, const toml::table& root, SceneSpec& s) {
  for (const toml::table& t : r.tables(root, "region")) {
    const Vec3 lo = r.vec3(r.required(t, "min", "[[region]]"), "min");
    const Vec3 hi = r.vec3(r.required(t, "max", "[[region]]"), "max");
    auto inside = [&](int i) {
      const Vec3& p = s.model.rest[static_cast<size_t>(i)];
      return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
    };
    int count = 0;
    SceneRegion region;
    region.label = "region " + std::to_string(s.regions.size() + 1) + " (line " +
                   std::to_string(t.source().begin.line) + ")";
    for (int i = 0; i < s.model.node_count(); ++i) {
      if (!inside(i)) continue;
      ++count;
      region.nodes.push_back(i);
      const auto k = static_cast<size_t>(i);
      if (auto* n = t.get("mass_scale")) s.model.mass_scale[k] = r.positive(*n, "mass_scale");
      if (auto* n = t.get("gamma_scale"))
        s.model.gamma_scale[k] = r.non_negative(*n, "gamma_scale");
      if (auto* n = t.get("anchor_scale"))
        s.model.anchor_scale[k] = r.non_negative(*n, "anchor_scale");
      if (auto* n = t.get("fixed")) s.model.fixed[k] = r.boolean(*n, "fixed");
      if (auto* n = t.get("force")) s.model.external_force[k] = r.vec3(*n, "force");
    }
    if (count == 0) r.fail(t, "[[region]] contains no node");
    s.regions.push_back(std::move(region));
    if (auto* n = t.get("kappa_scale")) {
      const double ks = r.positive(*n, "kappa_scale");
      for (Spring& sp : s.model.springs)
        if (inside(sp.i) && inside(sp.j)) sp.kappa_scale = ks;
    }
    if (auto* n = t.get("kd_scale")) {  // the dashpots of its springs and anchors (SPEC 10)
      const double ds = r.non_negative(*n, "kd_scale");
      for (Spring& sp : s.model.springs)
        if (inside(sp.i) && inside(sp.j)) sp.kd_scale = ds;
      s.model.anchor_kd_scale.resize(s.model.rest.size(), 1.0);
      for (int i = 0; i < s.model.node_count(); ++i)
        if (inside(i)) s.model.anchor_kd_scale[static_cast<size_t>(i)] = ds;
    }
  }
}

void read_perturbations(const Reader& r, const toml::table& root, SceneSpec& s) {
  for (const toml::table& t : r.tables(root, "perturb")) {
    Perturbation p;
    p.node = node_ref(r, s, r.required(t, "node", "[[perturb]]"), "perturb node");
    if (s.model.fixed[static_cast<size_t>(p.node)])
      r.fail(t, "perturb node " + std::to_string(p.node) + " is fixed");
    if (auto* n = t.get("displacement")) p.displacement = r.vec3(*n, "displacement");
    if (auto* n = t.get("velocity")) p.velocity = r.vec3(*n, "velocity");
    s.perturbations.push_back(p);
  }
}

void read_protocol(const Reader& r, const toml::table& root, SceneSpec& s) {
  double largest = 0;
  for (const auto& p : s.perturbations) largest = std::max(largest, p.displacement.norm());
  s.rules.reference = largest > 0 ? largest : 1.0;
  const toml::node* pn = root.get("protocol");
  if (!pn) return;
  const toml::table& t = r.table(*pn, "protocol");
  r.check_keys(t, "[protocol]");
  if (auto* n = t.get("max_iterations")) s.rules.max_iterations = read_max_iterations(r, *n);
  if (auto* n = t.get("restore_fraction"))
    s.rules.restore_fraction = r.positive(*n, "restore_fraction");
  if (auto* n = t.get("diverge_factor")) s.rules.diverge_factor = r.positive(*n, "diverge_factor");
  if (auto* n = t.get("reference")) s.rules.reference = r.positive(*n, "reference");
}

void read_cuts(const Reader& r, const toml::table& root, SceneSpec& s) {
  for (const toml::table& t : r.tables(root, "cut")) {
    CutEvent c;
    const long long it = r.integer(r.required(t, "iteration", "[[cut]]"), "iteration");
    if (it < 0 || it > 100000000) r.fail(t, "cut iteration must be in 0..100000000");
    c.iteration = static_cast<int>(it);
    const auto a = r.numbers(r.required(t, "from", "[[cut]]"), 2, "from ([x, z])");
    const auto b = r.numbers(r.required(t, "to", "[[cut]]"), 2, "to ([x, z])");
    c.from[0] = a[0], c.from[1] = a[1], c.to[0] = b[0], c.to[1] = b[1];
    s.cuts.push_back(c);
  }
}

void read_runs(const Reader& r, const toml::table& root, SceneSpec& s) {
  std::set<std::string> labels;
  for (const toml::table& t : r.tables(root, "run")) {
    RunSpec run{r.string(r.required(t, "label", "[[run]]"), "label"), s.params, s.rules};
    check_plain_text(run.label, "run label", r.path(), static_cast<int>(t.source().begin.line));
    if (run.label.empty() || !labels.insert(run.label).second)
      r.fail(t, "run label '" + run.label + "' is empty or used twice");
    read_params(r, t, "[[run]] '" + run.label + "'", run.params);
    if (run.params.zeta.has_value() != s.params.zeta.has_value())
      r.fail(t, "[[run]] '" + run.label + "' gives its damping as " +
                    (run.params.zeta ? "zeta where [params] gives gamma"
                                     : "gamma where [params] gives zeta") +
                    ": give it the same way in every table");
    if (auto* n = t.get("max_iterations")) run.rules.max_iterations = read_max_iterations(r, *n);
    s.runs.push_back(run);
  }
}

}  // namespace

SceneSpec parse_scene(const std::string& text, const std::string& path) {
  const Reader r(path);
  check_scene_text(text, path);
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    r.fail(static_cast<int>(e.source().begin.line), std::string(e.description()));
  }
  r.check_keys(root, "");
  SceneSpec s;
  s.path = path;
  if (auto* n = root.get("name")) {
    s.name = r.string(*n, "name");
    check_plain_text(s.name, "name", path, static_cast<int>(n->source().begin.line));
  }
  if (auto* n = root.get("description")) {
    s.description = r.string(*n, "description");
    check_plain_text(s.description, "description", path, static_cast<int>(n->source().begin.line));
  }
  read_geometry(r, root, s);
  read_regions(r, root, s);
  if (auto* pn = root.get("params")) {
    const toml::table& t = r.table(*pn, "params");
    r.check_keys(t, "[params]");
    read_params(r, t, "[params]", s.params);
  }
  read_perturbations(r, root, s);
  read_protocol(r, root, s);
  s.watched = s.perturbations.empty() ? 0 : s.perturbations.front().node;
  if (auto* n = root.get("watch")) s.watched = node_ref(r, s, *n, "watch");
  read_cuts(r, root, s);
  read_runs(r, root, s);
  scene_file::read_expectations(r, root, s);
  return s;
}

SceneSpec load_scene(const std::string& path) {
  return parse_scene(read_file_text(path, kMaxSceneBytes), path);
}

std::string resolve_scene(const std::string& text, const std::string& scenes_dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (text.find('/') != std::string::npos || scenes_dir.empty() || fs::exists(text, ec))
    return text;
  for (const std::string& name : {text, text + ".toml"}) {
    const fs::path p = fs::path(scenes_dir) / name;
    if (fs::is_regular_file(p, ec)) return p.string();
  }
  return text;
}

}  // namespace dampbound
