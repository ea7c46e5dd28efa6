#include "ui/tuner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <stdexcept>

#include "core/io/report.hpp"
#include "core/io/scene_file.hpp"
#include "core/physics/damping_ratio.hpp"
#include "dampbound/physics/bounds.hpp"

namespace dampbound::ui {

SceneSpec with_settled_rule(SceneSpec scene) {
  scene.rules.rule = StopRule::settled;
  return scene;
}

namespace {

/// A scene as the tuner runs it: a damping ratio given as `zeta` resolved into gamma_i (as
/// `dampbound gui SCENE` does; a scene resolved already is left as it is), the settled rule.
SceneSpec as_tuned(SceneSpec scene) {
  resolve_zeta(scene);
  return with_settled_rule(std::move(scene));
}

}  // namespace

std::string params_label(const Params& p) {
  std::string s = "gamma " + fmt(p.gamma) + ", m " + fmt(p.m) + ", kappa " + fmt(p.kappa) +
                  ", dt " + fmt(p.dt) + ", " + to_string(p.policy);
  if (p.policy == DampingPolicy::upper) s += " x" + fmt(p.factor);
  if (p.integrator != Integrator::semi_implicit_euler)
    s += ", " + std::string(to_string(p.integrator));
  if (p.kd != 0) s += ", kd " + fmt(p.kd);
  if (p.rayleigh_mass != 0) s += ", alpha " + fmt(p.rayleigh_mass);
  if (p.rayleigh_stiffness != 0) s += ", beta " + fmt(p.rayleigh_stiffness);
  return s;
}

LowerBoundCheck check_lower_bound(const Model& model) {
  LowerBoundCheck c;
  for (int i = 0; i < model.spec().node_count(); ++i) {
    const auto k = static_cast<size_t>(i);
    if (model.spec().fixed[k] || !(model.lower_bound[k] > 0)) continue;
    const double r = model.gamma[k] / model.lower_bound[k];
    ++c.nodes;
    c.below += r < 1 ? 1 : 0;
    if (c.worst >= 0 && std::abs(r - c.ratio) > 1e-12 * std::max(r, c.ratio)) c.uniform = false;
    if (c.worst < 0 || r < c.ratio) {
      c.worst = i;
      c.ratio = r;
      c.lower = model.lower_bound[k];
    }
  }
  return c;
}

namespace {

/// True when gamma_scale_i / (lower bound at m = kappa = 1)_i is the same at every free node
/// with a bound: gamma = zeta * 2 sqrt(m kappa) then gives every node the same ratio, without
/// resolving the scene (a plain mesh, or one resolved already, e.g. by `gui --zeta`).
bool uniform_ratio_per_gamma(const ModelSpec& spec) {
  Params unit;
  unit.m = unit.kappa = unit.gamma = 1;
  const Model m = compile_model(spec, unit);
  double first = -1;
  for (size_t i = 0; i < m.lower_bound.size(); ++i) {
    if (m.spec().fixed[i] || !(m.lower_bound[i] > 0)) continue;
    const double r = m.gamma[i] / m.lower_bound[i];
    if (first < 0) first = r;
    if (std::abs(r - first) > 1e-12 * first) return false;
  }
  return true;
}

}  // namespace

std::string zeta_text(const Model& model) {
  const DampingRatioRange r = damping_ratio_range(model);
  if (std::isnan(r.min)) return "-";
  if (std::abs(r.max - r.min) <= 1e-12 * r.max) return fmt(r.min);
  return fmt(r.min) + " .. " + fmt(r.max) + " over the nodes";
}

Tuner::Tuner(SceneSpec scene) { new_session(std::move(scene)); }

void Tuner::new_session(SceneSpec scene) {
  const bool given_zeta = scene.params.zeta.has_value();
  session_ = std::make_unique<Session>(as_tuned(std::move(scene)));
  criteria_.forget();  // nothing of the last scene's analysis stays on show
  session_->set_threads(0);  // the same bits on any count; big meshes step faster
  zeta_resolved_ = given_zeta || uniform_ratio_per_gamma(session_->scene().model);
  zeta_mode_ = given_zeta;
}

double Tuner::zeta() const {
  return params().gamma / lower_bound(params().m, params().kappa);
}

void Tuner::set_zeta_mode(bool on) {
  if (on && !zeta_resolved_) {
    // Resolve the scene's damping scales for the current ratio; the run starts over on the
    // resolved model (a Session's spec does not change under a run).
    const int watched = session_->watched();
    SceneSpec scene = session_->scene();
    scene.params = params();
    scene.params.zeta = zeta();
    scene.rules = session_->rules();
    for (RunSpec& r : scene.runs) r.params.zeta = r.params.gamma / lower_bound(r.params.m, r.params.kappa);
    new_session(std::move(scene));
    watch(watched);
    ++scene_version_;
    playing_ = false;
    on_new_trace();
    notice_ = "zeta mode: each node's gamma_i resolved from zeta (gamma_i = zeta 2 sqrt(m_i "
              "kappa_i)); the run restarted from the scene's start";
  }
  zeta_mode_ = on;
}

bool Tuner::set_zeta(double zeta, std::string* error) {
  if (const auto why = number_problem(zeta, true)) {
    if (error != nullptr) *error = "zeta " + *why;
    return false;
  }
  set_zeta_mode(true);
  Params p = params();
  p.gamma = gamma_of_zeta(zeta, p);
  return set_params(p, error);
}

bool Tuner::open_scene(const std::string& path, std::string* error) {
  try {
    set_scene(load_scene(path));
    return true;
  } catch (const std::exception& e) {
    if (error != nullptr) *error = e.what();
    return false;
  }
}

void Tuner::set_scene(SceneSpec scene) {
  new_session(std::move(scene));
  ++scene_version_;
  playing_ = false;
  notice_.clear();
  on_new_trace();
}

bool Tuner::set_params(const Params& given, std::string* error) {
  Params params = given;
  const Params& now = session_->params();
  // Zeta mode holds the ratio when m or kappa move, unless gamma itself was set.
  if (zeta_mode_ && params.gamma == now.gamma && (params.m != now.m || params.kappa != now.kappa))
    params.gamma = gamma_of_zeta(zeta(), params);
  if (const auto why = validate(params)) {
    if (error != nullptr) *error = *why;
    return false;
  }
  const bool same = now.m == params.m && now.kappa == params.kappa && now.gamma == params.gamma &&
                    now.dt == params.dt && now.policy == params.policy &&
                    now.factor == params.factor && now.integrator == params.integrator &&
                    now.kd == params.kd && now.rayleigh_mass == params.rayleigh_mass &&
                    now.rayleigh_stiffness == params.rayleigh_stiffness;
  if (!same && session_->state().iteration > 0) replayable_ = false;
  session_->set_params(params);
  return true;
}

void Tuner::set_max_iterations(int n) {
  StopRules r = session_->rules();
  if (r.max_iterations != (n < 1 ? 1 : n) && session_->state().iteration > 0)
    replayable_ = false;
  r.max_iterations = n < 1 ? 1 : n;
  session_->set_rules(r);
}

bool Tuner::set_playing(bool play) {
  if (play && !can_step()) {
    playing_ = false;
    return false;
  }
  playing_ = play;
  return true;
}

bool Tuner::can_step() const {
  return session_->result().outcome != Outcome::diverged &&
         session_->trace().size() < playback_.max_trace;
}

int Tuner::step(int n, double budget_seconds) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const auto over_budget = [&] {
    return budget_seconds >= 0 &&
           std::chrono::duration<double>(Clock::now() - t0).count() >= budget_seconds;
  };
  int taken = 0;
  const int springs_before = session_->model().spec().spring_count();
  for (; taken < n && can_step() && (taken == 0 || !over_budget()) &&
         !stop_.load(std::memory_order_relaxed);
       ++taken) {
    const Outcome before = session_->result().outcome;
    session_->step_once();
    const Outcome after = session_->result().outcome;
    if (after == Outcome::diverged) {
      ++taken;
      playing_ = false;
      notice_ = verdict_short(session_->result()) + ": the run stopped; reset to go on";
      break;
    }
    if (before == Outcome::running && after != Outcome::running && playback_.pause_at_verdict) {
      ++taken;
      playing_ = false;
      const bool proven = after == Outcome::settled &&
                          session_->result().iterations < session_->rules().max_iterations;
      notice_ = verdict_text(session_->result(), session_->rules()) + ": paused at the verdict" +
                (proven ? " (SPEC 8's proof: it cannot leave the band before the limit)"
                 : after == Outcome::settled || after == Outcome::not_settled
                     ? " (the iteration limit, where the settled rule decides)"
                     : "");
      break;
    }
  }
  if (session_->trace().size() >= playback_.max_trace) {
    playing_ = false;
    notice_ =
        "the trace is full (" + std::to_string(playback_.max_trace) + " steps): reset to go on";
  }
  total_steps_ += taken;
  if (taken > 0) ++state_version_;
  // The scene's own cuts happen inside a step: the renderer and the criteria must hear of them.
  if (session_->model().spec().spring_count() != springs_before) ++topology_;
  step_seconds_ += std::chrono::duration<double>(Clock::now() - t0).count();
  return taken;
}

int Tuner::advance() {
  budget_cut_ = {};
  if (!playing_) return 0;
  const int asked = playback_.steps_per_frame < 1 ? 1 : playback_.steps_per_frame;
  const int taken = step(asked, playback_.frame_budget_seconds);
  // Short of the count while still playing and able to step: the time budget ended it.
  if (taken < asked && playing_ && can_step()) budget_cut_ = {taken, asked};
  return taken;
}

void Tuner::reset() {
  session_->reset();
  notice_.clear();
  on_new_trace();
}

void Tuner::perturb() {
  replayable_ = false;
  session_->perturb();
  ++state_version_;
}

void Tuner::displace(int node, const Vec3& offset) {
  if (node < 0 || node >= session_->model().spec().node_count() || !offset.allFinite()) return;
  replayable_ = false;
  session_->displace(node, offset);
  ++state_version_;
}

void Tuner::watch(int node) {
  if (node < 0 || node >= session_->model().spec().node_count()) return;
  session_->set_watched(node);
}

int Tuner::cut(const std::vector<int>& springs) {
  if (springs.empty()) return 0;
  const int removed = session_->cut(springs);
  if (removed > 0) replayable_ = false;
  if (removed > 0) ++topology_, ++state_version_;
  notice_ = "cut " + plural(removed, "spring") + " at iteration " +
            std::to_string(session_->state().iteration);
  return removed;
}

Pin& Tuner::pin(const std::string& name) {
  Pin p;
  p.name = name.empty() ? params_label(params()) : name;
  p.scene = scene().name;
  p.params = params();
  p.rules = session_->rules();
  p.result = session_->result();
  p.watched = session_->watched();
  p.trace = session_->trace();
  TraceDecimator d(kPlotBuckets);
  p.reduced = d.update(p.trace);
  p.color = palette_color(next_color_++);
  p.replayable = replayable_;
  pins_.push_back(std::move(p));
  return pins_.back();
}

void Tuner::unpin(size_t index) {
  if (index < pins_.size()) pins_.erase(pins_.begin() + static_cast<std::ptrdiff_t>(index));
}

ImU32 Tuner::current_color() const {
  return palette_color(0);
}

double Tuner::max_displacement_now() const {
  const Model& m = session_->model();
  double d = 0.0;
  for (int i = 0; i < m.spec().node_count(); ++i) {
    const double di = displacement(m, session_->state(), i);
    if (!std::isfinite(di)) return std::numeric_limits<double>::infinity();
    d = std::max(d, di);
  }
  return d;
}

double Tuner::watched_displacement_now() const {
  const int w = session_->watched();
  return w >= 0 && w < session_->model().spec().node_count()
             ? displacement(session_->model(), session_->state(), w)
             : 0.0;
}

const std::vector<StepSample>& Tuner::reduced_trace() {
  return decimator_.update(session_->trace(), generation_);
}

void Tuner::on_new_trace() {
  replayable_ = true;
  ++generation_;
  ++topology_;
  ++state_version_;
}

}  // namespace dampbound::ui
