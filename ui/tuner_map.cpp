#include "ui/tuner_map.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/sweep/summary.hpp"
#include "core/sweep/trials.hpp"

namespace dampbound::ui {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool same_rules(const StopRules& a, const StopRules& b) {
  return a.max_iterations == b.max_iterations && a.restore_fraction == b.restore_fraction &&
         a.diverge_factor == b.diverge_factor && a.reference == b.reference && a.rule == b.rule;
}

bool same_view(const MapView& a, const MapView& b) {
  return a.x == b.x && a.y == b.y && a.decades == b.decades && a.finest == b.finest;
}

/// The parameters that are not on an axis are equal.
bool same_off_axis(const Params& a, const Params& b, const MapView& v) {
  for (MapParam p : {MapParam::m, MapParam::kappa, MapParam::gamma, MapParam::dt})
    if (p != v.x && p != v.y && get_param(a, p) != get_param(b, p)) return false;
  return a.policy == b.policy && a.factor == b.factor && a.integrator == b.integrator;
}

/// The current value is within the middle half of the window (log distance to the centre at
/// most decades / 2).
bool near_centre(double value, double centre, double decades) {
  return value > 0 && centre > 0 && std::abs(std::log10(value / centre)) <= decades / 2;
}

/// Solves a boundary equation for `var` with the other parameters from `p`; NaN when `var`
/// does not appear or has no positive solution.
double solve_lower(const MapBoundConstants& k, const Params& p, MapParam var) {
  // gamma = 2 C sqrt(m kappa) (paper eq. 5 at the worst node).
  const double C = k.lower, half = p.gamma / (2 * C);
  switch (var) {
    case MapParam::gamma: return 2 * C * std::sqrt(p.m * p.kappa);
    case MapParam::m: return half * half / p.kappa;
    case MapParam::kappa: return half * half / p.m;
    case MapParam::dt: return kNaN;
  }
  return kNaN;
}

double solve_exact(const MapBoundConstants& k, const Params& p, MapParam var) {
  // lambda_unit kappa dt^2 + 2 r gamma dt = 4 m: SPEC 7's lambda_max dt^2 < 4 - 2 c dt with
  // lambda_max = lambda_unit kappa / m and c = r gamma / m, multiplied by m.
  const double L = k.lambda_unit, r = k.rate_ratio;
  const double m = p.m, kap = p.kappa, g = p.gamma, dt = p.dt;
  switch (var) {
    case MapParam::gamma: return r > 0 ? (4 * m - L * kap * dt * dt) / (2 * r * dt) : kNaN;
    case MapParam::m: return (L * kap * dt * dt + 2 * r * g * dt) / 4;
    case MapParam::kappa: return (4 * m - 2 * r * g * dt) / (L * dt * dt);
    case MapParam::dt: return (-r * g + std::sqrt(r * g * r * g + 4 * L * kap * m)) / (L * kap);
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

std::vector<int> passes(int finest) {
  std::vector<int> out;
  finest = std::max(finest, 2);
  for (int n = 8; n < finest; n *= 2) out.push_back(n);
  out.push_back(finest);
  return out;
}

}  // namespace

const char* to_string(MapParam p) {
  switch (p) {
    case MapParam::m: return "m";
    case MapParam::kappa: return "kappa";
    case MapParam::gamma: return "gamma";
    case MapParam::dt: return "dt";
  }
  return "?";
}

std::string map_axis_label(MapParam p) {
  switch (p) {
    case MapParam::m: return "m (mass unit)";
    case MapParam::kappa: return "kappa (mass unit/s^2)";
    case MapParam::gamma: return "gamma (mass unit/s)";
    case MapParam::dt: return "dt (s)";
  }
  return "?";
}

double get_param(const Params& params, MapParam p) {
  switch (p) {
    case MapParam::m: return params.m;
    case MapParam::kappa: return params.kappa;
    case MapParam::gamma: return params.gamma;
    case MapParam::dt: return params.dt;
  }
  return kNaN;
}

void set_param(Params& params, MapParam p, double value) {
  switch (p) {
    case MapParam::m: params.m = value; break;
    case MapParam::kappa: params.kappa = value; break;
    case MapParam::gamma: params.gamma = value; break;
    case MapParam::dt: params.dt = value; break;
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

MapBoundConstants map_bound_constants(const SceneSpec& scene) {
  MapBoundConstants k;
  Params unit = scene.params;
  unit.m = unit.kappa = unit.gamma = 1;
  const Model model = make_model(scene, unit);
  double worst = kNaN, rate = kNaN;
  bool uniform = true;
  for (int i = 0; i < model.node_count(); ++i) {
    const auto n = static_cast<size_t>(i);
    if (model.fixed[n]) continue;
    // With gamma_i = gamma gamma_scale_i: gamma_i >= 2 sqrt(m_i kappa_i) iff
    // gamma >= 2 sqrt(m kappa) sqrt(mass_scale_i kappa_scale_i) / gamma_scale_i.
    if (model.gamma[n] > 0 && model.lower_bound[n] > 0) {
      const double c = model.lower_bound[n] / (2 * model.gamma[n]);
      if (!(c <= worst)) worst = c;
    }
    const double r = model.gamma[n] / model.mass[n];
    if (std::isnan(rate)) rate = r;
    else if (std::abs(r - rate) > 1e-12 * std::max(r, rate)) uniform = false;
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
        worst ? "paper lower bound, worst node (eq. 5)" : "paper lower bound 2 sqrt(m kappa) (eq. 5)",
        MapLineKind::paper,
        [&](const Params& p, MapParam v) { return solve_lower(k, p, v); }, base, view, x_edges,
        y_edges, samples));
  }
  if (std::isfinite(k.lambda_unit) && k.lambda_unit > 0 && std::isfinite(k.rate_ratio) &&
      base.integrator == Integrator::semi_implicit_euler)
    lines.push_back(boundary(
        "exact linear limit (SPEC 7)", MapLineKind::exact_linear,
        [&](const Params& p, MapParam v) { return solve_exact(k, p, v); }, base, view, x_edges,
        y_edges, samples));
  if (!k.safe.row_sum.empty() && base.integrator == Integrator::semi_implicit_euler)
    lines.push_back(boundary(
        "safe bound, every node (SPEC 9)", MapLineKind::safe,
        [&](const Params& p, MapParam v) {
          const SafeAxis axis = v == MapParam::m       ? SafeAxis::m
                                : v == MapParam::kappa ? SafeAxis::kappa
                                : v == MapParam::gamma ? SafeAxis::gamma
                                                       : SafeAxis::dt;
          return safe_edge(k.safe, axis, p.m, p.kappa, p.gamma, p.dt);
        },
        base, view, x_edges, y_edges, samples));
  lines.erase(std::remove_if(lines.begin(), lines.end(),
                             [](const MapLine& l) { return l.x.size() < 2; }),
              lines.end());
  return lines;
}

MapPanel map_result_panel(const MapResult& r) {
  MapPanel p;
  p.title = "Outcome around the current point (" + std::to_string(r.x_edges.size() - 1) + " x " +
            std::to_string(r.y_edges.size() - 1) + ")";
  p.x_label = map_axis_label(r.view.x);
  p.y_label = map_axis_label(r.view.y);
  p.x_log = p.y_log = true;
  p.x_edges = r.x_edges;
  p.y_edges = r.y_edges;
  p.cells.reserve(r.cells.size());
  p.iterations.reserve(r.cells.size());
  for (const TrialResult& t : r.cells) {
    // As build_stability_map does: under the settled rule (SPEC 8) a settled cell is shaded by
    // its settled iteration, and a run that entered the band but was out of it at the limit is
    // told from one that never entered.
    MapCell c = MapCell::empty;
    double it = t.iterations;
    switch (t.outcome) {
      case Outcome::restored: c = MapCell::restored; break;
      case Outcome::settled: c = MapCell::restored, it = t.settled_at; break;
      case Outcome::not_restored: c = MapCell::not_restored; break;
      case Outcome::not_settled:
        c = t.first_entry > 0 ? MapCell::entered_left : MapCell::not_restored;
        break;
      case Outcome::diverged: c = MapCell::diverged; break;
      case Outcome::running: break;
    }
    p.cells.push_back(c);
    p.iterations.push_back(it);
  }
  p.lines = r.lines;
  return p;
}

TunerMap::~TunerMap() {
  stop();
}

void TunerMap::reap(bool all) {
  for (auto it = retired_.begin(); it != retired_.end();) {
    if (all || (*it)->done) {
      (*it)->cancel = true;
      if ((*it)->thread.joinable()) (*it)->thread.join();
      it = retired_.erase(it);
    } else {
      ++it;
    }
  }
}

void TunerMap::stop() {
  if (job_) {
    job_->cancel = true;
    retired_.push_back(std::move(job_));
    job_.reset();
  }
  reap(true);
}

void TunerMap::wait() {
  if (job_ && job_->thread.joinable()) job_->thread.join();
}

std::shared_ptr<const MapResult> TunerMap::result() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return result_;
}

std::string TunerMap::unsupported() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return unsupported_;
}

void TunerMap::follow(const SceneSpec& scene, std::uint64_t scene_key, const Params& params,
                      const StopRules& rules, const MapView& view) {
  reap(false);
  const bool restart =
      !started_ || scene_key != scene_key_ || !same_rules(rules, rules_) ||
      !same_view(view, view_) || !same_off_axis(params, centre_, view) ||
      !near_centre(get_param(params, view.x), get_param(centre_, view.x), view.decades) ||
      !near_centre(get_param(params, view.y), get_param(centre_, view.y), view.decades);
  if (!restart) return;
  if (job_) {  // cancelled first, so that it publishes nothing of the old scene
    job_->cancel = true;
    retired_.push_back(std::move(job_));
    job_.reset();
  }
  if (scene_key != scene_key_) {
    std::lock_guard<std::mutex> lock(mutex_);
    bounds_.reset();
  }
  scene_key_ = scene_key;
  start(scene, params, rules, view);
}

void TunerMap::start(const SceneSpec& scene, const Params& centre, const StopRules& rules,
                     const MapView& view) {
  if (job_) {  // cancelled; it ends after its current step, joined later
    job_->cancel = true;
    retired_.push_back(std::move(job_));
    job_.reset();
  }
  started_ = true;
  ++starts_;
  centre_ = centre;
  rules_ = rules;
  view_ = view;
  SceneSpec s = scene;
  s.params = centre;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    unsupported_ = batch_kernel_unsupported(s);
    if (!(get_param(centre, view.x) > 0) || !(get_param(centre, view.y) > 0))
      unsupported_ = std::string("the map's axes are logarithmic: ") + to_string(view.x) +
                     " and " + to_string(view.y) + " must be > 0";
    if (!unsupported_.empty()) {
      result_.reset();
      return;
    }
  }
  job_ = std::make_shared<Job>();
  Job* job = job_.get();
  job->thread = std::thread([this, job, s = std::move(s), centre, rules, view] {
    try {
      std::shared_ptr<const MapBoundConstants> k;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        k = bounds_;
      }
      if (!k) {
        k = std::make_shared<const MapBoundConstants>(map_bound_constants(s));
        std::lock_guard<std::mutex> lock(mutex_);
        if (!job->cancel) bounds_ = k;
      }
      int pass = 0;
      const std::vector<int> sizes = passes(view.finest);
      for (int n : sizes) {
        const auto t0 = std::chrono::steady_clock::now();
        auto r = std::make_shared<MapResult>();
        r->view = view;
        r->base = centre;
        r->max_iterations = rules.max_iterations;
        r->rule = rules.rule;
        r->x_edges = map_log_edges(get_param(centre, view.x), view.decades, n);
        r->y_edges = map_log_edges(get_param(centre, view.y), view.decades, n);
        r->cells = run_map_trials(s, centre, rules,
                                  map_trials(centre, view.x, map_cell_centres(r->x_edges), view.y,
                                             map_cell_centres(r->y_edges)),
                                  &job->cancel);
        if (job->cancel) break;
        r->lines = map_bound_lines(*k, centre, view, r->x_edges, r->y_edges);
        r->pass = ++pass;
        r->finest = n == sizes.back();
        r->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::lock_guard<std::mutex> lock(mutex_);
        if (job->cancel) break;
        result_ = std::move(r);
      }
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!job->cancel) unsupported_ = e.what();
    }
    job->done = true;
  });
}

}  // namespace dampbound::ui
