// The scene format's one table (core/io/scene_keys.hpp). Defaults come from the structs the
// reader fills, so the reference says what the code does.
#include "core/io/scene_keys.hpp"

#include <cctype>
#include <sstream>

#include "core/io/mesh.hpp"
#include "dampbound/physics/params.hpp"
#include "dampbound/run/protocol.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {
namespace {

std::string num(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}
std::string yes_no(bool b) {
  return b ? "true" : "false";
}
std::string quoted(const char* s) {
  return std::string("\"") + s + "\"";
}

std::vector<SceneKey> make_keys() {
  const Params p;
  const StopRules rules = default_stop_rules();
  const GridSpec grid;
  const MeshSprings mesh;
  const Expectation expect;
  const std::string scales = "a node's own scales";
  return {
      {"", "name", "string", "none", "the scene's name, shown by the tuner and reports"},
      {"", "description", "string", "none", "one line on what the scene shows"},
      {"", "watch", "node", "the first perturbed node",
       "the watched node: an index, or [a, b] on a [grid]"},

      {"[grid]", "nx", "integer", "required", "nodes along x; node (a, b) sits at (a h, 0, b h)"},
      {"[grid]", "nz", "integer", "required", "nodes along z; node (a, b) has index a nz + b"},
      {"[grid]", "spacing", "number", "required", "h, the distance between neighbours (cm)"},
      {"[grid]", "diagonals", "boolean", yes_no(grid.diagonals),
       "one diagonal spring (a, b)-(a+1, b+1) per cell"},
      {"[grid]", "anchors", "boolean", yes_no(grid.anchors),
       "a zero-rest-length spring from each node to its rest position"},

      {"[[node]]", "x", "[x, y, z]", "required", "rest position (cm)"},
      {"[[node]]", "fixed", "boolean", "false", "the node never moves"},
      {"[[node]]", "mass_scale", "number", "1", "m_i = m mass_scale"},
      {"[[node]]", "gamma_scale", "number", "1", "gamma_i = gamma gamma_scale"},
      {"[[node]]", "anchor_scale", "number", "0",
       "anchor stiffness kappa anchor_scale (0: no anchor)"},
      {"[[node]]", "force", "[x, y, z]", "[0, 0, 0]", "external force f_i"},

      {"[[spring]]", "nodes", "[node, node]", "required", "the two ends (indices, or [a, b])"},
      {"[[spring]]", "rest_length", "number", "the rest distance of its ends", "rest length (cm)"},
      {"[[spring]]", "kappa_scale", "number", "1", "kappa_ij = kappa kappa_scale"},
      {"[[spring]]", "kd_scale", "number", "1", "dashpot kd_ij = kd kd_scale"},

      {"[mesh]", "file", "string", "required",
       "the mesh file, relative to the scene's folder (.obj, .msh, .node/.ele, .vtk)"},
      {"[mesh]", "format", "string", "from the extension", "obj, msh, tetgen or vtk"},
      {"[mesh]", "scale", "number", num(mesh.scale), "cm per file unit"},
      {"[mesh]", "bend", "boolean", yes_no(mesh.bend),
       "a bending spring across every edge shared by two triangles or quads"},
      {"[mesh]", "anchors", "boolean", yes_no(mesh.anchors), "an anchor at every vertex"},
      {"[mesh]", "density", "number", "0 (off)",
       "lumped masses: mass_scale_i = density x the cells' measure at i / their corner count"},
      {"[mesh]", "young", "number", "0 (off)",
       "spring stiffness from the cells: kappa_scale_e = young x measure / l_e^2"},
      {"[mesh]", "region_array", "string", "the first cell array",
       "VTK: the cell array that holds the region tags"},

      {"[[mesh_region]]", "tag", "integer", "one of tag or name",
       "the region's tag (Gmsh physical tag, TetGen attribute, VTK cell array value)"},
      {"[[mesh_region]]", "name", "string", "one of tag or name", "a Gmsh physical name"},
      {"[[mesh_region]]", "fixed", "boolean", "false", "its nodes never move"},
      {"[[mesh_region]]", "mass_scale", "number", "1", "multiplies " + scales},
      {"[[mesh_region]]", "kappa_scale", "number", "1",
       "multiplies the springs with both ends in the region"},
      {"[[mesh_region]]", "gamma_scale", "number", "1", "multiplies " + scales},
      {"[[mesh_region]]", "anchor_scale", "number", "1", "sets its nodes' anchor scale"},
      {"[[mesh_region]]", "force", "[x, y, z]", "[0, 0, 0]", "external force on each node"},
      {"[[mesh_region]]", "displacement", "[x, y, z]", "none",
       "perturbs each node by this at t = 0"},
      {"[[mesh_region]]", "kd_scale", "number", "1",
       "multiplies the dashpots of its springs and anchors"},

      {"[[region]]", "min", "[x, y, z]", "required", "the box's low corner in rest space (cm)"},
      {"[[region]]", "max", "[x, y, z]", "required", "the box's high corner (cm)"},
      {"[[region]]", "mass_scale", "number", "unchanged",
       "sets the mass scale of the nodes inside"},
      {"[[region]]", "kappa_scale", "number", "unchanged",
       "sets kappa_scale of the springs with both ends inside"},
      {"[[region]]", "gamma_scale", "number", "unchanged", "sets the nodes' gamma scale"},
      {"[[region]]", "anchor_scale", "number", "unchanged", "sets the nodes' anchor scale"},
      {"[[region]]", "fixed", "boolean", "unchanged", "the nodes inside never move"},
      {"[[region]]", "force", "[x, y, z]", "unchanged",
       "external force on each node inside (a load: the rest state is then no equilibrium)"},
      {"[[region]]", "kd_scale", "number", "unchanged",
       "sets the dashpot scale of the springs and anchors inside"},

      {"[params]", "m", "number", num(p.m), "node mass (mass unit)"},
      {"[params]", "kappa", "number", num(p.kappa),
       "spring and anchor stiffness (mass unit / s^2)"},
      {"[params]", "gamma", "number", num(p.gamma),
       "nodal viscous damping (mass unit / s); excludes zeta"},
      {"[params]", "zeta", "number", "none",
       "damping ratio: gamma = zeta 2 sqrt(m_i kappa_i); excludes gamma"},
      {"[params]", "dt", "number", num(p.dt), "time step (s)"},
      {"[params]", "policy", "string", quoted(to_string(p.policy)),
       "damping policy: " + one_of(policy_names())},
      {"[params]", "factor", "number", num(p.factor), "multiplier of gamma_hi for policy upper"},
      {"[params]", "integrator", "string", quoted(to_string(p.integrator)),
       one_of(integrator_names())},
      {"[params]", "kd", "number", num(p.kd),
       "dashpot along every spring and anchor (mass unit / s)"},
      {"[params]", "rayleigh_mass", "number", num(p.rayleigh_mass),
       "Rayleigh alpha (1/s): force -alpha m_i v_i"},
      {"[params]", "rayleigh_stiffness", "number", num(p.rayleigh_stiffness),
       "Rayleigh beta (s): force -beta (K(x) v)_i"},

      {"[[perturb]]", "node", "node", "required", "the perturbed node (not fixed)"},
      {"[[perturb]]", "displacement", "[x, y, z]", "[0, 0, 0]", "displacement at t = 0 (cm)"},
      {"[[perturb]]", "velocity", "[x, y, z]", "[0, 0, 0]", "velocity at t = 0 (cm/s)"},

      {"[protocol]", "max_iterations", "integer", std::to_string(rules.max_iterations),
       "the run's step limit (1..1e8)"},
      {"[protocol]", "restore_fraction", "number", num(rules.restore_fraction),
       "the band: restored below fraction x reference"},
      {"[protocol]", "diverge_factor", "number", num(rules.diverge_factor),
       "diverged above factor x reference"},
      {"[protocol]", "reference", "number", "the largest perturbation displacement",
       "the displacement the band and the divergence limit scale (cm)"},

      {"[[cut]]", "iteration", "integer", "required", "the step after which the cut happens"},
      {"[[cut]]", "from", "[x, z]", "required", "one end of the cutting segment (cm)"},
      {"[[cut]]", "to", "[x, z]", "required", "the other end (cm)"},

      {"[[run]]", "label", "string", "required", "the run's name, unique in the scene"},
      {"[[run]]", "max_iterations", "integer", "[protocol]'s", "the run's step limit"},

      {"[[expect]]", "run", "string", "the scene's own [params]", "the [[run]] it checks"},
      {"[[expect]]", "rule", "string", quoted(to_string(expect.rule)),
       "the verdict rule: first-entry or settled"},
      {"[[expect]]", "outcome", "string", "none",
       "first-entry: restored, diverged, not_restored; settled: settled, diverged, not_settled"},
      {"[[expect]]", "iterations", "[min, max]", "none", "the outcome's iteration (inclusive)"},
      {"[[expect]]", "first_entry", "[min, max]", "none", "the first iteration inside the band"},
      {"[[expect]]", "left", "boolean", "none", "settled rule: left the band after entering it"},
      {"[[expect]]", "left_at", "[min, max]", "none", "settled rule: the first exit"},
      {"[[expect]]", "settled_at", "[min, max]", "none",
       "settled rule: inside the band from here to the limit"},
      {"[[expect]]", "max_displacement_below", "number", "none",
       "the largest displacement at the last iteration is below this (cm)"},
      {"[[expect]]", "unstabilisable_max", "number", "none", "at most this many node-steps"},
      {"[[expect]]", "violations_max", "number", "none", "at most this many bound violations"},
      {"[[expect]]", "violations_min", "number", "none", "at least this many bound violations"},
      {"[[expect]]", "mass_scale_dt", "number", "none",
       "SPEC 11: judge mass scaling for this target step (s); the keys above then judge the run "
       "at it with the scaled masses"},
      {"[[expect]]", "added_mass_percent", "[min, max]", "none",
       "with mass_scale_dt: the added mass, % of the free mass"},
      {"[[expect]]", "scaled_nodes", "[min, max]", "none",
       "with mass_scale_dt: the nodes given mass"},
      {"[[expect]]", "dt_limit_min", "number", "none",
       "the exact dt limit at rest (at the run's damping) is at least this (s)"},
      {"[[expect]]", "substeps_max", "integer", "none",
       "frame_dt / n is below the exact dt limit for some n <= this"},
      {"[[expect]]", "frame_dt", "number", "the run's dt", "the frame time substeps_max divides (s)"},
  };
}

}  // namespace

const std::vector<SceneSection>& scene_sections() {
  static const std::vector<SceneSection> sections = {
      {"", "the top level: names and the watched node", ""},
      {"[grid]",
       "a generated plane of nodes (the paper's geometry); one of [grid], [[node]], [mesh]", ""},
      {"[[node]]", "explicit nodes, one table each; springs follow in [[spring]]", ""},
      {"[[spring]]", "a spring between two [[node]] entries", ""},
      {"[mesh]", "nodes and springs from a mesh file (docs/meshes.md)", ""},
      {"[[mesh_region]]", "scales, loads or perturbations for a region the mesh file tags", ""},
      {"[[region]]", "scales for the nodes inside a box of rest space", ""},
      {"[params]", "the parameters that --m, --kappa, ... override", ""},
      {"[[perturb]]", "the perturbation at t = 0; one or more", ""},
      {"[protocol]", "the run's limits and the band it is judged by", ""},
      {"[[cut]]", "removes every spring whose xz-projection crosses a segment", ""},
      {"[[run]]", "a named variant, overlaid by figure and run by check; any [params] key too",
       "[params]"},
      {"[[expect]]", "what check asserts; give at least one of the asserting keys", ""},
  };
  return sections;
}

const std::vector<SceneKey>& scene_keys() {
  static const std::vector<SceneKey> keys = make_keys();
  return keys;
}

/// "[[node]]" -> "node": the top-level key that opens a section.
static std::string_view bare(std::string_view name) {
  while (!name.empty() && name.front() == '[') name.remove_prefix(1);
  while (!name.empty() && name.back() == ']') name.remove_suffix(1);
  return name;
}

bool scene_key_allowed(std::string_view section, std::string_view key) {
  if (section.empty())
    for (const SceneSection& s : scene_sections())
      if (!s.name.empty() && bare(s.name) == key) return true;
  for (const SceneKey& k : scene_keys())
    if (k.section == section && k.key == key) return true;
  for (const SceneSection& s : scene_sections())
    if (s.name == section && !s.inherits.empty()) return scene_key_allowed(s.inherits, key);
  return false;
}

std::string scene_format_markdown() {
  std::ostringstream os;
  os << "# Scene format reference\n\n"
        "Every section and key of a scene file (TOML), from the table the reader checks keys "
        "against (core/io/scene_keys.cpp; written by `scripts/scene-reference.sh`, a test fails "
        "when this page is stale). A key not listed here is refused with the file and line. "
        "Units: cm, s and any consistent mass unit. A scene has one geometry: [grid], [[node]] "
        "or [mesh].\n";
  for (const SceneSection& s : scene_sections()) {
    os << "\n## " << (s.name.empty() ? "Top level" : "`" + s.name + "`") << "\n\n"
       << static_cast<char>(std::toupper(static_cast<unsigned char>(s.meaning[0])))
       << s.meaning.substr(1) << ".\n\n"
       << "| key | type | default | meaning |\n|---|---|---|---|\n";
    for (const SceneKey& k : scene_keys())
      if (k.section == s.name)
        os << "| `" << k.key << "` | " << k.type << " | " << k.default_value << " | " << k.meaning
           << " |\n";
  }
  return os.str();
}

}  // namespace dampbound
