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
};

const MapAxis& axis(MapParam p) {
  return kMapAxes[static_cast<int>(p)];
}

}  // namespace

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

std::vector<TrialParams> map_trials(const Params& base, MapParam x, const std::vector<double>& xs,
                                    MapParam y, const std::vector<double>& ys) {
  std::vector<TrialParams> out;
  out.reserve(xs.size() * ys.size());
  for (double yv : ys)
    for (double xv : xs) {
      Params p = base;
      set_param(p, x, xv);
      set_param(p, y, yv);
      out.push_back({p.m, p.kappa, p.gamma, p.dt, p.factor, p.kd, p.rayleigh_mass, p.rayleigh_stiffness});
    }
  return out;
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
