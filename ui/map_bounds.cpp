#include "ui/map_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/physics/detail/numbers.hpp"
#include "core/physics/integrate.hpp"
#include "core/sweep/summary.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound::ui {

namespace {


/// Solves a boundary equation for `var` with the other parameters from `p`; NaN when `var`
/// does not appear or has no positive solution.
double solve_lower(const MapBoundConstants& k, const Params& p, MapParam var) {
  // gamma = 2 C sqrt(m kappa) (paper eq. 5 at the worst node).
  const double C = k.lower, half = p.gamma / (2 * C);
  switch (var) {
    case MapParam::gamma:
      return 2 * C * std::sqrt(p.m * p.kappa);
    case MapParam::m:
      return half * half / p.kappa;
    case MapParam::kappa:
      return half * half / p.m;
    case MapParam::dt:
    case MapParam::kd:
    case MapParam::rayleigh_mass:
    case MapParam::rayleigh_stiffness:
      return kNaN;  // eq. 5 is the nodal lower bound: the other damping does not enter it
  }
  return kNaN;
}

double solve_exact(const MapBoundConstants& k, const Params& p, MapParam var) {
  // lambda_unit kappa dt^2 + 2 r gamma dt = 4 m: SPEC 7's lambda_max dt^2 < 4 - 2 c dt with
  // lambda_max = lambda_unit kappa / m and c = r gamma / m, multiplied by m.
  const double L = k.lambda_unit, r = k.rate_ratio;
  const double m = p.m, kap = p.kappa, g = p.gamma, dt = p.dt;
  switch (var) {
    case MapParam::gamma:
      return r > 0 ? (4 * m - L * kap * dt * dt) / (2 * r * dt) : kNaN;
    case MapParam::m:
      return (L * kap * dt * dt + 2 * r * g * dt) / 4;
    case MapParam::kappa:
      return (4 * m - 2 * r * g * dt) / (L * dt * dt);
    case MapParam::dt:
      return (-r * g + std::sqrt(r * g * r * g + 4 * L * kap * m)) / (L * kap);
    case MapParam::kd:
    case MapParam::rayleigh_mass:
    case MapParam::rayleigh_stiffness:
      return kNaN;  // not drawn with that damping (map_bound_lines)
  }
  return kNaN;
}

/// The curve of `solve` across the window: sampled along x solving for y, or along y solving
/// for x when y does not appear in the equation.
template <class Solve>
MapLine boundary(const std::string& label, MapLineKind kind, Solve solve, const Params& base,
                 const MapView& v, const std::vector<double>& xe, const std::vector<double>& ye,
                 int samples) {
  MapLine line;
  line.label = label;
  line.kind = kind;
  const bool along_x = std::isfinite(solve(base, v.y)) || !std::isfinite(solve(base, v.x));
  const std::vector<double>& e = along_x ? xe : ye;
  const MapParam free = along_x ? v.x : v.y, solved = along_x ? v.y : v.x;
  const double l0 = std::log10(e.front()), l1 = std::log10(e.back());
  for (int i = 0; i <= samples; ++i) {
    Params p = base;
    const double t = std::pow(10.0, l0 + (l1 - l0) * i / samples);
    set_param(p, free, t);
    const double s = solve(p, solved);
    if (!(std::isfinite(s) && s > 0)) continue;
    (along_x ? line.x : line.y).push_back(t);
    (along_x ? line.y : line.x).push_back(s);
  }
  return line;
}

}  // namespace

MapBoundConstants map_bound_constants(const SceneSpec& scene) {
  MapBoundConstants k;
  Params unit = scene.params;
  unit.m = unit.kappa = unit.gamma = 1;
  const Model model = compile_model(scene.model, unit);
  double worst = kNaN, rate = kNaN;
  bool uniform = true;
  for (int i = 0; i < model.spec().node_count(); ++i) {
    const auto n = static_cast<size_t>(i);
    if (model.spec().fixed[n]) continue;
    // With gamma_i = gamma gamma_scale_i: gamma_i >= 2 sqrt(m_i kappa_i) iff
    // gamma >= 2 sqrt(m kappa) sqrt(mass_scale_i kappa_scale_i) / gamma_scale_i.
    if (model.gamma[n] > 0 && model.lower_bound[n] > 0) {
      const double c = model.lower_bound[n] / (2 * model.gamma[n]);
      if (!(c <= worst)) worst = c;
    }
    const double r = model.gamma[n] / model.mass[n];
    if (std::isnan(rate))
      rate = r;
    else if (std::abs(r - rate) > 1e-12 * std::max(r, rate))
      uniform = false;
  }
  k.lower = worst;
  k.rate_ratio = uniform ? rate : kNaN;
  k.lambda_unit = uniform && std::isfinite(rate) ? unit_stiffness_eigenvalue(scene) : kNaN;
  k.safe = unit_safe_bound(scene);
  return k;
}

std::vector<MapLine> map_bound_lines(const MapBoundConstants& k, const Params& base,
                                     const MapView& view, const std::vector<double>& x_edges,
                                     const std::vector<double>& y_edges, int samples) {
  std::vector<MapLine> lines;
  if (std::isfinite(k.lower) && k.lower > 0) {
    const bool worst = std::abs(k.lower - 1) > 1e-12;
    lines.push_back(boundary(
        worst ? "paper lower bound, worst node (eq. 5)"
              : "paper lower bound 2 sqrt(m kappa) (eq. 5)",
        MapLineKind::paper, [&](const Params& p, MapParam v) { return solve_lower(k, p, v); }, base,
        view, x_edges, y_edges, samples));
  }
  // The exact and safe lines below are the nodal damping's (SPEC 7, 9): with dashpots or
  // Rayleigh damping (SPEC 10) in the window they are not the limits, so they are not drawn.
  const bool nodal_only = !map_runs_plain(base, view);
  if (nodal_only && std::isfinite(k.lambda_unit) && k.lambda_unit > 0 &&
      std::isfinite(k.rate_ratio) && integrator_traits(base.integrator).paper_step)
    lines.push_back(boundary(
        "exact linear limit", MapLineKind::exact_linear,
        [&](const Params& p, MapParam v) { return solve_exact(k, p, v); }, base, view, x_edges,
        y_edges, samples));
  if (nodal_only && !k.safe.row_sum.empty() &&
      integrator_traits(base.integrator).paper_step)
    lines.push_back(boundary(
        "safe bound, every node", MapLineKind::safe,
        [&](const Params& p, MapParam v) {
          if (other_damping_axis(v)) return kNaN;
          const SafeAxis axis = v == MapParam::m       ? SafeAxis::m
                                : v == MapParam::kappa ? SafeAxis::kappa
                                : v == MapParam::gamma ? SafeAxis::gamma
                                                       : SafeAxis::dt;
          return safe_edge(k.safe, axis, p.m, p.kappa, p.gamma, p.dt);
        },
        base, view, x_edges, y_edges, samples));
  lines.erase(
      std::remove_if(lines.begin(), lines.end(), [](const MapLine& l) { return l.x.size() < 2; }),
      lines.end());
  return lines;
}

}  // namespace dampbound::ui
