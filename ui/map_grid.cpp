#include "ui/map_grid.hpp"

#include <cmath>

#include "core/sweep/trials.hpp"

namespace dampbound::ui {

namespace {

/// One row per MapParam, in the enum's order: its name, its axis label with the unit, and
/// where it lives in Params.
struct MapAxis {
  const char* name;
  const char* label;
  double Params::*member;
};
constexpr MapAxis kMapAxes[] = {
    {"m", "m (mass unit)", &Params::m},
    {"kappa", "kappa (mass unit/s^2)", &Params::kappa},
    {"gamma", "gamma (mass unit/s)", &Params::gamma},
    {"dt", "dt (s)", &Params::dt},
    {"kd", "kd (mass unit/s)", &Params::kd},
    {"rayleigh_mass", "rayleigh_mass alpha (1/s)", &Params::rayleigh_mass},
    {"rayleigh_stiffness", "rayleigh_stiffness beta (s)", &Params::rayleigh_stiffness},
};

const MapAxis& axis(MapParam p) {
  return kMapAxes[static_cast<int>(p)];
}

}  // namespace

bool other_damping_axis(MapParam p) {
  return p == MapParam::kd || p == MapParam::rayleigh_mass || p == MapParam::rayleigh_stiffness;
}

bool has_other_damping(const Params& params) {
  return params.kd != 0 || params.rayleigh_mass != 0 || params.rayleigh_stiffness != 0;
}

const char* to_string(MapParam p) {
  return axis(p).name;
}

std::string map_axis_label(MapParam p) {
  return axis(p).label;
}

double get_param(const Params& params, MapParam p) {
  return params.*axis(p).member;
}

void set_param(Params& params, MapParam p, double value) {
  params.*axis(p).member = value;
}

std::vector<double> map_log_edges(double centre, double decades, int n) {
  std::vector<double> e;
  const double l = std::log10(centre);
  for (int i = 0; i <= n; ++i) e.push_back(std::pow(10.0, l - decades + 2 * decades * i / n));
  return e;
}

std::vector<double> map_cell_centres(const std::vector<double>& edges) {
  std::vector<double> c;
  for (size_t i = 0; i + 1 < edges.size(); ++i) c.push_back(std::sqrt(edges[i] * edges[i + 1]));
  return c;
}

std::vector<Params> map_cell_params(const Params& base, MapParam x, const std::vector<double>& xs,
                                    MapParam y, const std::vector<double>& ys) {
  std::vector<Params> out;
  out.reserve(xs.size() * ys.size());
  for (double yv : ys)
    for (double xv : xs) {
      Params p = base;
      set_param(p, x, xv);
      set_param(p, y, yv);
      out.push_back(p);
    }
  return out;
}

std::vector<TrialParams> map_trials(const Params& base, MapParam x, const std::vector<double>& xs,
                                    MapParam y, const std::vector<double>& ys) {
  std::vector<TrialParams> out;
  for (const Params& p : map_cell_params(base, x, xs, y, ys))
    out.push_back({p.m, p.kappa, p.gamma, p.dt, p.factor, p.kd, p.rayleigh_mass,
                   p.rayleigh_stiffness});
  return out;
}

std::vector<TrialResult> run_map_cells(const SceneSpec& scene, const std::vector<Params>& cells,
                                       const StopRules& rules, const std::atomic<bool>* cancel) {
  std::vector<TrialResult> out;
  out.reserve(cells.size());
  SceneSpec s = scene;
  for (const Params& p : cells) {
    s.params = p;  // run_reference takes kd, alpha, beta and the integrator from here
    out.push_back(run_reference(
        s, p.policy, rules,
        {p.m, p.kappa, p.gamma, p.dt, p.factor, p.kd, p.rayleigh_mass, p.rayleigh_stiffness},
        cancel));
    if (cancel != nullptr && cancel->load()) return {};
  }
  return out;
}

bool map_runs_plain(const Params& centre, const MapView& view) {
  return has_other_damping(centre) || other_damping_axis(view.x) || other_damping_axis(view.y);
}

std::string map_unsupported(const SceneSpec& scene, const Params& centre, const MapView& view) {
  Params nodal = centre;  // SPEC 10 damping is run cell by cell: only the rest can refuse
  nodal.kd = nodal.rayleigh_mass = nodal.rayleigh_stiffness = 0;
  std::string why = batch_kernel_unsupported(scene, nodal).value_or("");
  if (why.empty() && (!(get_param(centre, view.x) > 0) || !(get_param(centre, view.y) > 0)))
    why = std::string("the map's axes are logarithmic: ") + to_string(view.x) + " and " +
          to_string(view.y) + " must be > 0" +
          (other_damping_axis(view.x) || other_damping_axis(view.y)
               ? " (turn that damping on in the parameters)"
               : "");
  return why;
}

std::vector<TrialResult> run_map_trials(const SceneSpec& scene, const Params& base,
                                        const StopRules& rules,
                                        const std::vector<TrialParams>& trials,
                                        const std::atomic<bool>* cancel) {
  SceneSpec s = scene;
  s.params = base;  // the kernel takes the integrator from the scene's parameters
  return run_batched(s, base.policy, rules, trials, KernelIsa::best, cancel);
}

}  // namespace dampbound::ui
