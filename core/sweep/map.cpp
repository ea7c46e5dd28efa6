#include "core/sweep/map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/io/format.hpp"
#include "core/sweep/summary.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

namespace {

/// Cells along one axis. Distinct values are grouped, in order, into cells at least
/// (range / max_bins) wide (in log on a log axis), with edges half-way between neighbouring
/// groups: at most about max_bins cells, one per value when there are few, and never an
/// empty cell between two values of the grid.
struct Binning {
  std::vector<double> edges;
  std::vector<double> firsts;  // the first value of each cell

  int bin(double v) const {
    const auto it = std::upper_bound(firsts.begin(), firsts.end(), v);
    return std::max(0, static_cast<int>(it - firsts.begin()) - 1);
  }
};

Binning make_binning(std::vector<double> v, int max_bins, bool log) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  auto fwd = [log](double x) { return log ? std::log(x) : x; };
  auto inv = [log](double x) { return log ? std::exp(x) : x; };
  Binning b;
  if (v.size() == 1) {
    const double x = fwd(v[0]);
    const double pad = log ? 0.1 : (v[0] != 0 ? 0.25 * std::fabs(v[0]) : 0.5);
    b.edges = {inv(x - pad), inv(x + pad)};
    b.firsts = v;
    return b;
  }
  const double width =
      static_cast<int>(v.size()) <= max_bins ? 0.0 : (fwd(v.back()) - fwd(v.front())) / max_bins;
  std::vector<double> lasts;
  for (size_t i = 0; i < v.size(); ++i) {
    if (b.firsts.empty() || fwd(v[i]) - fwd(b.firsts.back()) >= width * (1 - 1e-9)) {
      b.firsts.push_back(v[i]);
      lasts.push_back(v[i]);
    } else {
      lasts.back() = v[i];
    }
  }
  const size_t n = b.firsts.size();
  // Outer edges: half the spacing of the neighbouring values beyond the outermost ones.
  const double lo_gap = fwd(v[1]) - fwd(v[0]);
  const double hi_gap = fwd(v.back()) - fwd(v[v.size() - 2]);
  b.edges.push_back(inv(fwd(b.firsts[0]) - 0.5 * lo_gap));
  for (size_t k = 0; k + 1 < n; ++k)
    b.edges.push_back(inv(0.5 * (fwd(lasts[k]) + fwd(b.firsts[k + 1]))));
  b.edges.push_back(inv(fwd(lasts.back()) + 0.5 * hi_gap));
  if (!log && v[0] >= 0 && b.edges[0] < 0) b.edges[0] = 0;
  return b;
}

/// Fills the cells of `panel` from (x, y, row) triples.
template <class XY>
void fill_cells(MapPanel& panel, const Binning& bx, const Binning& by,
                const std::vector<const SweepRow*>& rows, XY xy) {
  const size_t nx = bx.edges.size() - 1, ny = by.edges.size() - 1;
  std::vector<std::array<std::uint64_t, 4>> count(nx * ny, {0, 0, 0, 0});
  std::vector<double> iter_sum(nx * ny, 0);
  for (const SweepRow* r : rows) {
    const auto [x, y] = xy(*r);
    const size_t c = static_cast<size_t>(by.bin(y)) * nx + static_cast<size_t>(bx.bin(x));
    const bool settled = r->outcome == Outcome::settled;
    const int k = r->outcome == Outcome::restored || settled ? 0
                  : r->outcome == Outcome::diverged         ? 2
                  : r->first_entry > 0                      ? 3  // SPEC 8: entered, then left
                                                            : 1;
    ++count[c][static_cast<size_t>(k)];
    if (k == 0) iter_sum[c] += settled ? r->settled_at : r->iterations;
  }
  panel.x_edges = bx.edges;
  panel.y_edges = by.edges;
  panel.cells.assign(nx * ny, MapCell::empty);
  panel.iterations.assign(nx * ny, 0);
  for (size_t c = 0; c < nx * ny; ++c) {
    const auto& n = count[c];
    if (n[0] + n[1] + n[2] + n[3] == 0) continue;
    const size_t k = static_cast<size_t>(std::max_element(n.begin(), n.end()) - n.begin());
    panel.cells[c] = static_cast<MapCell>(k);
    if (n[0]) panel.iterations[c] = iter_sum[c] / static_cast<double>(n[0]);
  }
}

MapLine horizontal(const std::string& label, MapLineKind kind, double y, const MapPanel& p) {
  return {label, kind, {p.x_edges.front(), p.x_edges.back()}, {y, y}};
}

MapLine vertical(const std::string& label, MapLineKind kind, double x, const MapPanel& p) {
  return {label, kind, {x, x}, {p.y_edges.front(), p.y_edges.back()}};
}

/// SPEC 7 with gamma = 2 zeta sqrt(m kappa): unstable above
/// zeta_max(r) = (2/dt - lambda_1 r dt/2) / (2 sqrt r), r = kappa/m.
double zeta_max(double r, double lambda_unit, double dt) {
  // spec7_gamma_max at m = 1 is gamma_max/m: 2/dt - lambda dt/2, rounded as written above.
  return spec7_gamma_max(lambda_unit * r, 1, dt) / (2 * std::sqrt(r));
}

/// The ratio r at which zeta_max(r) = zeta: the positive root in sqrt(r) of
/// (lambda_1 dt/2) s^2 + 2 zeta s - 2/dt = 0.
double critical_ratio(double zeta, double lambda_unit, double dt) {
  const double s = 2 * (-zeta + std::sqrt(zeta * zeta + lambda_unit)) / (lambda_unit * dt);
  return s * s;
}

/// A column of the sweep CSV as a map axis: how to read it from a row and how to set it on
/// one (for the boundary search; unset: no boundary along it).
struct Column {
  std::string name, label;
  double (*get)(const SweepRow&);
  void (*set)(SweepRow&, double);
};

const std::vector<Column>& columns() {
  static const std::vector<Column> c = {
      {"m", "m (mass unit)", [](const SweepRow& r) { return r.m; }, nullptr},
      {"kappa", "kappa (mass unit/s^2)", [](const SweepRow& r) { return r.kappa; }, nullptr},
      {"kappa/m", "kappa/m (1/s^2)", [](const SweepRow& r) { return r.kappa / r.m; }, nullptr},
      {"gamma", "gamma (mass unit/s)", [](const SweepRow& r) { return r.gamma; },
       [](SweepRow& r, double v) { r.gamma = v; }},
      {"zeta", "zeta = gamma / (2 sqrt(m kappa))", [](const SweepRow& r) { return r.zeta; },
       [](SweepRow& r, double v) { r.gamma = v * lower_bound(r.m, r.kappa); }},
      {"dt", "dt (s)", [](const SweepRow& r) { return r.dt; }, [](SweepRow& r, double v) { r.dt = v; }},
      {"factor", "factor of the upper bound", [](const SweepRow& r) { return r.factor; }, nullptr},
      {"kd", "kd, dashpots (mass unit/s)", [](const SweepRow& r) { return r.kd; },
       [](SweepRow& r, double v) { r.kd = v; }},
      {"rayleigh_mass", "Rayleigh alpha (1/s)", [](const SweepRow& r) { return r.rayleigh_mass; },
       [](SweepRow& r, double v) { r.rayleigh_mass = v; }},
      {"rayleigh_stiffness", "Rayleigh beta (s)",
       [](const SweepRow& r) { return r.rayleigh_stiffness; },
       [](SweepRow& r, double v) { r.rayleigh_stiffness = v; }},
  };
  return c;
}

const Column& column(const std::string& name) {
  for (const Column& c : columns())
    if (c.name == name) return c;
  std::string known;
  for (const Column& c : columns()) known += (known.empty() ? "" : ", ") + c.name;
  throw InputError("--axes: unknown column '" + name + "' (" + known + ")");
}

/// One panel of columns x against y, the other columns held at `held`'s values; the exact
/// linear boundary (SPEC 7 and 10's closed form) found along y by bisection at 300 x values.
MapPanel axis_panel(const std::vector<const SweepRow*>& all, const SweepRow& held,
                    const Column& cx, const Column& cy, double lambda_unit,
                    std::optional<double> dashpot_ratio, bool fixed_policy) {
  auto drawn = [&](const std::string& n) { return cx.name == n || cy.name == n; };
  auto held_column = [&](const Column& c) {
    if (drawn(c.name) || c.name == "kappa/m" || c.name == "zeta") return false;  // derived
    if (c.name == "gamma" && drawn("zeta")) return false;
    if ((c.name == "m" || c.name == "kappa") && drawn("kappa/m")) return false;
    return true;
  };
  std::vector<const SweepRow*> rows;
  std::string fixed;
  for (const Column& c : columns()) {
    if (!held_column(c)) continue;
    bool varies = false;
    for (const SweepRow* r : all) varies = varies || c.get(*r) != c.get(held);
    if (varies) fixed += (fixed.empty() ? " (" : ", ") + c.name + " = " + format_number(c.get(held));
  }
  for (const SweepRow* r : all) {
    bool same = true;
    for (const Column& c : columns()) same = same && (!held_column(c) || c.get(*r) == c.get(held));
    if (same) rows.push_back(r);
  }
  MapPanel p;
  p.title = "outcome over " + cx.name + " and " + cy.name;
  if (!fixed.empty()) p.title += fixed + ")";
  p.x_label = cx.label;
  p.y_label = cy.label;
  std::vector<double> xs, ys;
  for (const SweepRow* r : rows) {
    xs.push_back(cx.get(*r));
    ys.push_back(cy.get(*r));
  }
  auto spans_decade = [](const std::vector<double>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return *lo > 0 && *hi / *lo > 10;
  };
  p.x_log = spans_decade(xs);
  p.y_log = spans_decade(ys);
  const Binning bx = make_binning(xs, 200, p.x_log), by = make_binning(ys, 200, p.y_log);
  fill_cells(p, bx, by, rows,
             [&](const SweepRow& r) { return std::pair<double, double>(cx.get(r), cy.get(r)); });
  const bool have_lambda = std::isfinite(lambda_unit) && lambda_unit > 0;
  if (!fixed_policy || !have_lambda || !cx.set || !cy.set) return p;
  const bool dashpots = held.kd != 0 || cx.name == "kd" || cy.name == "kd";
  if (dashpots && !dashpot_ratio) return p;
  auto unstable = [&](double x, double y) {
    SweepRow r = held;
    cx.set(r, x);
    cy.set(r, y);
    return linearly_unstable(r, lambda_unit, dashpot_ratio.value_or(0));
  };
  auto at = [](double a, double b, double f, bool log) {
    return log ? std::exp(std::log(a) + (std::log(b) - std::log(a)) * f) : a + (b - a) * f;
  };
  MapLine l{"exact linear limit" + std::string(has_spec10_damping(held) || dashpots ||
                                                           cx.name.rfind("rayleigh", 0) == 0 ||
                                                           cy.name.rfind("rayleigh", 0) == 0
                                                       ? " (with dashpot/Rayleigh damping)"
                                                       : ""),
            MapLineKind::exact_linear, {}, {}};
  const double x0 = std::max(p.x_edges.front(), 0.0), x1 = p.x_edges.back();
  const double y0 = std::max(p.y_edges.front(), 0.0), y1 = p.y_edges.back();
  for (int k = 0; k <= 300; ++k) {
    const double x = at(x0 > 0 ? x0 : x1 * 1e-6, x1, k / 300.0, p.x_log && x0 > 0);
    const double x_here = k == 0 && !p.x_log ? x0 : x;
    double lo = y0 > 0 || !p.y_log ? y0 : y1 * 1e-6, hi = y1;
    const bool u_lo = unstable(x_here, lo), u_hi = unstable(x_here, hi);
    if (u_lo == u_hi) {  // no boundary along y here
      l.x.push_back(x_here);
      l.y.push_back(NAN);
      continue;
    }
    for (int it = 0; it < 60; ++it) {
      const double mid = p.y_log && lo > 0 ? std::sqrt(lo * hi) : 0.5 * (lo + hi);
      (unstable(x_here, mid) == u_lo ? lo : hi) = mid;
    }
    l.x.push_back(x_here);
    l.y.push_back(0.5 * (lo + hi));
  }
  p.lines.push_back(l);
  return p;
}

}  // namespace

const std::vector<std::string>& map_axis_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Column& c : columns()) n.push_back(c.name);
    return n;
  }();
  return names;
}

StabilityMap build_stability_map(const SweepTable& table, double lambda_unit,
                                 const MapOptions& opt) {
  if (table.rows.empty()) throw InputError("map: the sweep has no rows");
  if (!opt.axes.empty()) {
    std::vector<const SweepRow*> all;
    for (const SweepRow& r : table.rows) all.push_back(&r);
    const SweepRow* first = &table.rows.front();
    if (opt.dt) {
      first = nullptr;
      for (const SweepRow& r : table.rows)
        if (r.dt == *opt.dt && !first) first = &r;
      if (!first) throw InputError("--dt: no trials with dt = " + format_number(*opt.dt));
    }
    const SweepRow& held = *first;
    const std::optional<DampingPolicy> policy = table.header.policy;
    StabilityMap map;
    map.max_iterations =
        std::atoi(definition_value(table.header.definition, "max-iter").value_or("0").c_str());
    map.title = table.header.scene_name + ": policy " +
                (policy ? std::string(to_string(*policy)) : std::string("?")) + ", " +
                std::to_string(map.max_iterations) + " iterations";
    map.rule = table.header.rule;
    map.side_by_side = true;
    if (map.rule == StopRule::settled) map.title += ", settled rule";
    map.summary = summary_lines(table.rows, policy, lambda_unit, opt.dashpot_ratio);
    for (const auto& [x, y] : opt.axes) {
      const Column &cx = column(x), &cy = column(y);
      if (&cx == &cy) throw InputError("--axes: " + x + ":" + y + " draws a column against itself");
      map.panels.push_back(axis_panel(all, held, cx, cy, lambda_unit, opt.dashpot_ratio,
                                      policy == DampingPolicy::fixed));
      map.panels.back().title = table.header.scene_name + ": " + map.panels.back().title;
    }
    return map;
  }
  const std::optional<DampingPolicy> policy = table.header.policy;
  const bool upper = policy == DampingPolicy::upper;
  const bool gamma_policy = policy == DampingPolicy::fixed || policy == DampingPolicy::clamp;
  // A policy this build does not know is shown as the definition says it.
  const std::string policy_name =
      policy ? to_string(*policy)
             : definition_value(table.header.definition, "policy").value_or("");
  const double dt = opt.dt ? *opt.dt : table.rows.front().dt;
  std::vector<const SweepRow*> rows;
  for (const SweepRow& r : table.rows)
    if (r.dt == dt) rows.push_back(&r);
  if (rows.empty()) throw InputError("--dt: no trials with dt = " + format_number(dt));
  const bool have_lambda = std::isfinite(lambda_unit) && lambda_unit > 0;

  StabilityMap map;
  map.max_iterations =
      std::atoi(definition_value(table.header.definition, "max-iter").value_or("0").c_str());
  map.title = table.header.scene_name + ": policy " + policy_name + ", dt = " + format_number(dt) +
              " s, " + std::to_string(map.max_iterations) + " iterations";
  map.summary = summary_lines(table.rows, policy, lambda_unit);
  map.rule = table.header.rule;
  if (map.rule == StopRule::settled) map.title += ", settled rule";
  auto yval = [upper](const SweepRow& r) { return upper ? r.factor : r.zeta; };

  // Panel 1: kappa/m (log) against zeta, or against the factor of the upper bound.
  MapPanel ratio;
  ratio.title = "outcome over kappa/m and " + std::string(upper ? "factor" : "zeta");
  ratio.x_label = "kappa/m (1/s^2)";
  ratio.y_label = upper ? "factor of the upper bound (eq. 6)" : "zeta = gamma / (2 sqrt(m kappa))";
  ratio.x_log = true;
  std::vector<double> xs, ys;
  for (const SweepRow* r : rows) {
    xs.push_back(r->kappa / r->m);
    ys.push_back(yval(*r));
  }
  const Binning bx = make_binning(xs, opt.ratio_bins, true);
  const Binning by = make_binning(ys, 40, false);
  fill_cells(ratio, bx, by, rows,
             [&](const SweepRow& r) { return std::pair<double, double>(r.kappa / r.m, yval(r)); });
  if (gamma_policy)
    ratio.lines.push_back(
        horizontal("paper: lower bound, zeta = 1 (eq. 5)", MapLineKind::paper, 1.0, ratio));
  if (upper)
    ratio.lines.push_back(
        horizontal("paper: upper bound, factor = 1 (eq. 6)", MapLineKind::paper, 1.0, ratio));
  if (have_lambda) {
    if (gamma_policy) {
      MapLine l{"exact linear limit gamma_max", MapLineKind::exact_linear, {}, {}};
      const double a = std::log(ratio.x_edges.front()), b = std::log(ratio.x_edges.back());
      for (int k = 0; k <= 400; ++k) {
        const double r = std::exp(a + (b - a) * k / 400);
        const double z = zeta_max(r, lambda_unit, dt);
        l.x.push_back(r);
        l.y.push_back(z > 0 ? z : NAN);
      }
      ratio.lines.push_back(l);
    }
    const double r_crit = 4 / (lambda_unit * dt * dt);
    if (r_crit > ratio.x_edges.front() && r_crit < ratio.x_edges.back())
      ratio.lines.push_back(vertical("dt = 2/sqrt(lambda_max): undamped limit",
                                     MapLineKind::dt_limit, r_crit, ratio));
  }
  map.panels.push_back(ratio);

  // Panels 2..: m against kappa for each zeta (or factor) value, as the paper's grid.
  std::vector<double> slices = ys, ms, ks;
  std::sort(slices.begin(), slices.end());
  slices.erase(std::unique(slices.begin(), slices.end()), slices.end());
  for (const SweepRow* r : rows) {
    ms.push_back(r->m);
    ks.push_back(r->kappa);
  }
  // Log axes when the grid spans more than a decade: the boundaries kappa = r m are then
  // straight diagonals and the small masses, where the mesh diverges, get room.
  auto spans_decade = [](const std::vector<double>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return *lo > 0 && *hi / *lo > 10;
  };
  const bool log_m = spans_decade(ms), log_k = spans_decade(ks);
  const Binning bm = make_binning(ms, opt.grid_bins, log_m);
  const Binning bk = make_binning(ks, opt.grid_bins, log_k);
  if (static_cast<int>(slices.size()) > opt.max_slices || bm.edges.size() < 3 ||
      bk.edges.size() < 3)
    return map;
  for (double s : slices) {
    MapPanel p;
    p.title = (upper ? "factor = " : "zeta = ") + format_number(s);
    p.x_label = "m (mass unit)";
    p.y_label = "kappa (mass unit/s^2)";
    p.x_log = log_m;
    p.y_log = log_k;
    std::vector<const SweepRow*> sub;
    for (const SweepRow* r : rows)
      if (yval(*r) == s) sub.push_back(r);
    fill_cells(p, bm, bk, sub,
               [](const SweepRow& r) { return std::pair<double, double>(r.m, r.kappa); });
    if (have_lambda) {
      const double x0 = p.x_edges.front(), x1 = p.x_edges.back();
      const double r =
          gamma_policy ? critical_ratio(s, lambda_unit, dt) : 4 / (lambda_unit * dt * dt);
      char ratio_text[32];
      c_snprintf(ratio_text, sizeof ratio_text, "%.4g", r);
      p.lines.push_back({gamma_policy
                             ? std::string("exact linear limit: kappa/m = ") + ratio_text
                             : std::string("dt = 2/sqrt(lambda_max): kappa/m = ") + ratio_text,
                         gamma_policy ? MapLineKind::exact_linear : MapLineKind::dt_limit,
                         {x0, x1},
                         {r * x0, r * x1}});
    }
    map.panels.push_back(p);
  }
  return map;
}

}  // namespace dampbound
