#include "ui/map_grid.hpp"

#include <cmath>
#include <limits>

namespace dampbound::ui {

const char* to_string(MapParam p) {
  switch (p) {
    case MapParam::m:
      return "m";
    case MapParam::kappa:
      return "kappa";
    case MapParam::gamma:
      return "gamma";
    case MapParam::dt:
      return "dt";
  }
  return "?";
}

std::string map_axis_label(MapParam p) {
  switch (p) {
    case MapParam::m:
      return "m (mass unit)";
    case MapParam::kappa:
      return "kappa (mass unit/s^2)";
    case MapParam::gamma:
      return "gamma (mass unit/s)";
    case MapParam::dt:
      return "dt (s)";
  }
  return "?";
}

double get_param(const Params& params, MapParam p) {
  switch (p) {
    case MapParam::m:
      return params.m;
    case MapParam::kappa:
      return params.kappa;
    case MapParam::gamma:
      return params.gamma;
    case MapParam::dt:
      return params.dt;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void set_param(Params& params, MapParam p, double value) {
  switch (p) {
    case MapParam::m:
      params.m = value;
      break;
    case MapParam::kappa:
      params.kappa = value;
      break;
    case MapParam::gamma:
      params.gamma = value;
      break;
    case MapParam::dt:
      params.dt = value;
      break;
  }
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
      out.push_back({p.m, p.kappa, p.gamma, p.dt, p.factor});
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
