#include "dampbound/run/scene.hpp"

#include <cmath>
#include <string>

#include "core/physics/damping_ratio.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

ModelSpec make_grid(const GridSpec& g) {
  // Each side first: nx * nz of two large sides overflows before it is compared.
  if (g.nx < 1 || g.nz < 1 || g.nx > 4000000 || g.nz > 4000000 ||
      static_cast<long long>(g.nx) * g.nz > 4000000)
    throw InputError("grid: nx and nz must be >= 1 with nx * nz <= 4000000, got " +
                     std::to_string(g.nx) + " x " + std::to_string(g.nz));
  if (const auto why = number_problem(g.spacing, false)) throw InputError("grid: spacing " + *why);
  ModelSpec m;
  auto index = [&](int a, int b) { return a * g.nz + b; };
  for (int a = 0; a < g.nx; ++a)
    for (int b = 0; b < g.nz; ++b) {
      const int i = add_node(m, Vec3(a * g.spacing, 0, b * g.spacing));
      if (g.anchors) m.anchor_scale[static_cast<size_t>(i)] = 1;
    }
  for (int a = 0; a < g.nx; ++a)
    for (int b = 0; b < g.nz; ++b) {
      if (a + 1 < g.nx) add_spring(m, index(a, b), index(a + 1, b));
      if (b + 1 < g.nz) add_spring(m, index(a, b), index(a, b + 1));
      if (g.diagonals && a + 1 < g.nx && b + 1 < g.nz) add_spring(m, index(a, b), index(a + 1, b + 1));
    }
  return m;
}

SceneSpec paper_plane_scene(int n) {
  if (n < 1 || n > 2000)
    throw InputError("paper_plane_scene: n must be in 1..2000, got " + std::to_string(n));
  SceneSpec s;
  s.name = "paper-plane";
  s.description = "Paper sec. 3: " + std::to_string(n) + "x" + std::to_string(n) +
                  " planar mesh, anchors, node (" + std::to_string(n / 2) + "," +
                  std::to_string(n / 2) + ") perturbed 5 cm along y";
  GridSpec g;
  g.nx = g.nz = n;
  g.spacing = 0.57;
  s.grid = g;
  s.model = make_grid(g);
  s.watched = (n / 2) * n + n / 2;
  Perturbation p;
  p.node = s.watched;
  p.displacement = Vec3(0.0, 5.0, 0.0);
  s.perturbations.push_back(p);
  return s;
}

std::optional<std::string> validate(const SceneSpec& scene) {
  const ModelSpec& m = scene.model;
  const int n = m.node_count();
  if (n == 0) return std::string("the scene has no node");
  const size_t nodes = static_cast<size_t>(n);
  if (m.rest.size() != nodes || m.mass_scale.size() != nodes || m.gamma_scale.size() != nodes ||
      m.anchor_scale.size() != nodes || m.fixed.size() != nodes)
    return std::string("the scene's per-node arrays differ in length");
  auto node = [&](int i) { return i >= 0 && i < n; };
  auto at = [](const char* what, size_t i) { return std::string(what) + "[" + std::to_string(i) + "] "; };
  for (size_t i = 0; i < nodes; ++i) {
    if (!m.rest[i].allFinite()) return at("rest", i) + "must be finite";
    if (const auto why = number_problem(m.mass_scale[i], false)) return at("mass_scale", i) + *why;
    if (const auto why = number_problem(m.gamma_scale[i], true)) return at("gamma_scale", i) + *why;
    if (const auto why = number_problem(m.anchor_scale[i], true)) return at("anchor_scale", i) + *why;
  }
  for (size_t k = 0; k < m.springs.size(); ++k) {
    const Spring& sp = m.springs[k];
    if (!node(sp.i) || !node(sp.j) || sp.i == sp.j)
      return "spring " + std::to_string(k) + ": nodes must be two different indices in 0.." +
             std::to_string(n - 1);
  }
  if (!node(scene.watched))
    return "watched node " + std::to_string(scene.watched) + " is not in 0.." + std::to_string(n - 1);
  for (const Perturbation& p : scene.perturbations) {
    if (!node(p.node))
      return "perturbed node " + std::to_string(p.node) + " is not in 0.." + std::to_string(n - 1);
    if (!p.displacement.allFinite() || !p.velocity.allFinite())
      return "the perturbation of node " + std::to_string(p.node) + " must be finite";
  }
  return std::nullopt;
}

State initial_state(const SceneSpec& scene) {
  State s = rest_state(scene.model);
  for (const Perturbation& p : scene.perturbations) {
    s.x[static_cast<size_t>(p.node)] += p.displacement;
    s.v[static_cast<size_t>(p.node)] += p.velocity;
  }
  return s;
}

namespace {
double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

/// Proper or touching intersection of segments pq and rs in the plane.
bool segments_cross(const double p[2], const double q[2], const double r[2], const double s[2]) {
  const double d1 = cross2(q[0] - p[0], q[1] - p[1], r[0] - p[0], r[1] - p[1]);
  const double d2 = cross2(q[0] - p[0], q[1] - p[1], s[0] - p[0], s[1] - p[1]);
  const double d3 = cross2(s[0] - r[0], s[1] - r[1], p[0] - r[0], p[1] - r[1]);
  const double d4 = cross2(s[0] - r[0], s[1] - r[1], q[0] - r[0], q[1] - r[1]);
  // Collinear segments (d1 = d2 = 0) run along each other: that is no crossing.
  return d1 * d2 <= 0 && d3 * d4 <= 0 && !(d1 == 0 && d2 == 0);
}
}  // namespace

std::vector<int> springs_crossing(const ModelSpec& model, const std::vector<Vec3>& x,
                                  const double from[2], const double to[2]) {
  std::vector<int> out;
  for (int k = 0; k < model.spring_count(); ++k) {
    const Spring& s = model.springs[static_cast<size_t>(k)];
    const Vec3& a = x[static_cast<size_t>(s.i)];
    const Vec3& b = x[static_cast<size_t>(s.j)];
    const double p[2] = {a.x(), a.z()}, q[2] = {b.x(), b.z()};
    if (segments_cross(p, q, from, to)) out.push_back(k);
  }
  return out;
}

void resolve_zeta(SceneSpec& scene) {
  const bool base = scene.params.zeta.has_value();
  for (const RunSpec& r : scene.runs)
    if (r.params.zeta.has_value() != base)
      throw InputError(scene.path + ": [[run]] '" + r.label + "': " +
                       (base ? "gives gamma where [params] gives zeta"
                             : "gives zeta where [params] gives gamma") +
                       "; give the damping the same way in every table");
  if (!base) return;
  // The runs share the scene's spec, transformed once; each takes its own m, kappa and zeta.
  for (RunSpec& r : scene.runs) resolve_zeta(r.params);
  resolve_zeta(scene.model, scene.params);
}

}  // namespace dampbound
