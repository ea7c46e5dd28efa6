#include "ui/tuner_map.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>


namespace dampbound::ui {

namespace {

bool same_rules(const StopRules& a, const StopRules& b) {
  return a.max_iterations == b.max_iterations && a.restore_fraction == b.restore_fraction &&
         a.diverge_factor == b.diverge_factor && a.reference == b.reference && a.rule == b.rule;
}

bool same_view(const MapView& a, const MapView& b) {
  return a.x == b.x && a.y == b.y && a.decades == b.decades && a.finest == b.finest;
}

/// The parameters that are not on an axis are equal.
bool same_off_axis(const Params& a, const Params& b, const MapView& v) {
  for (MapParam p : kMapParams)
    if (p != v.x && p != v.y && get_param(a, p) != get_param(b, p)) return false;
  return a.policy == b.policy && a.factor == b.factor && a.integrator == b.integrator;
}

/// The current value is within the middle half of the window (log distance to the centre at
/// most decades / 2).
bool near_centre(double value, double centre, double decades) {
  return value > 0 && centre > 0 && std::abs(std::log10(value / centre)) <= decades / 2;
}

std::vector<int> passes(int finest) {
  std::vector<int> out;
  finest = std::max(finest, 2);
  for (int n = 8; n < finest; n *= 2) out.push_back(n);
  out.push_back(finest);
  return out;
}

}  // namespace

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

void TunerMap::retire_job() {
  if (!job_) return;
  job_->cancel = true;
  retired_.push_back(std::move(job_));
  job_.reset();
}

void TunerMap::stop() {
  retire_job();
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

void TunerMap::follow(std::shared_ptr<const SceneSpec> scene, std::uint64_t scene_key,
                      const Params& params,
                      const StopRules& rules, const MapView& view) {
  reap(false);
  const bool restart =
      !started_ || scene_key != scene_key_ || !same_rules(rules, rules_) ||
      !same_view(view, view_) || !same_off_axis(params, centre_, view) ||
      !near_centre(get_param(params, view.x), get_param(centre_, view.x), view.decades) ||
      !near_centre(get_param(params, view.y), get_param(centre_, view.y), view.decades);
  if (!restart) return;
  retire_job();  // cancelled first, so that it publishes nothing of the old scene
  if (scene_key != scene_key_) {
    std::lock_guard<std::mutex> lock(mutex_);
    bounds_.reset();
    result_.reset();  // the last scene's map is not this one's, not even until the first pass
  }
  scene_key_ = scene_key;
  start(std::move(scene), params, rules, view);
}

void TunerMap::start(std::shared_ptr<const SceneSpec> scene, const Params& centre,
                     const StopRules& rules, const MapView& view) {
  started_ = true;
  ++starts_;
  centre_ = centre;
  rules_ = rules;
  view_ = view;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    unsupported_ = map_unsupported(*scene, centre, view);
    if (!unsupported_.empty()) {
      result_.reset();
      return;
    }
  }
  job_ = std::make_shared<Job>();
  Job* job = job_.get();
  job->thread = std::thread([this, job, scene = std::move(scene), centre, rules, view] {
    try {
      SceneSpec s = *scene;  // here, not on the frame: it copies the mesh
      s.params = centre;
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
        const std::vector<double> xs = map_cell_centres(r->x_edges),
                                  ys = map_cell_centres(r->y_edges);
        r->plain = map_runs_plain(centre, view);
        r->cells = r->plain ? run_map_cells(s, map_cell_params(centre, view.x, xs, view.y, ys),
                                            rules, &job->cancel)
                            : run_map_trials(s, centre, rules,
                                             map_trials(centre, view.x, xs, view.y, ys),
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
