#include "core/analysis/criteria_safe.hpp"
#include "core/analysis/damping_limits.hpp"
#include "core/physics/integrate.hpp"
#include "ui/tuner_criteria.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <utility>
#include <vector>

namespace dampbound::ui {

namespace {
bool same_key(const Params& a, const Params& b) {
  return a.m == b.m && a.kappa == b.kappa && a.gamma == b.gamma && a.dt == b.dt &&
         a.integrator == b.integrator && a.kd == b.kd && a.rayleigh_mass == b.rayleigh_mass &&
         a.rayleigh_stiffness == b.rayleigh_stiffness;
}

/// Dashpots or Rayleigh damping (SPEC 10) besides the nodal damping.
bool other_damping(const Params& p) {
  return p.kd != 0 || p.rayleigh_mass != 0 || p.rayleigh_stiffness != 0;
}

/// gamma_i / m_i equal at every free node: the exact radius is a cheap per-mode formula.
bool uniform_rate(const Model& m) {
  double r0 = -1;
  for (size_t i = 0; i < m.mass.size(); ++i) {
    if (m.spec().fixed[i]) continue;
    const double r = m.gamma[i] / m.mass[i];
    if (r0 < 0) r0 = r;
    if (std::abs(r - r0) > 1e-12 * std::max(r0, 1e-300)) return false;
  }
  return true;
}

int free_node_count(const Model& model) {
  return static_cast<int>(std::count(model.spec().fixed.begin(), model.spec().fixed.end(), 0));
}

/// The analysis itself (SPEC 7), linearised at positions x; nullopt when x is not finite or
/// the solver fails.
std::optional<ExactStability> analyse(const Model& model, const std::vector<Vec3>& x,
                                      const Params& params, double factor_budget,
                                      const std::shared_ptr<SharedAnalysis>& shared) {
  for (const Vec3& p : x)
    if (!p.allFinite()) return std::nullopt;
  try {
    ExactOptions o;
    o.with_radius = uniform_rate(model);  // Arnoldi on a non-uniform mesh can take seconds
    o.max_factor_flops = factor_budget;  // a big 3-D mesh: what Lanczos proves, not hours
    o.shared = shared;  // a change of gamma, dt or the damping: the spectrum as it was
    if (!exact_not_computed_reason(model, params).empty()) return std::nullopt;
    ExactStability e = exact_stability(model, x, params, o);
    return e;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

double seconds_now() {
  using Clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}
}  // namespace

std::string exact_not_computed_reason(const Model& model, const Params& params) {
  if (!other_damping(params)) return "";
  // SPEC 10's limits (core's exact_stability takes them from the general damping matrix).
  if (!integrator_traits(params.integrator).paper_step)
    return std::string("with dashpot or Rayleigh damping it is derived for the paper's "
                       "semi-implicit step only, not ") +
           to_string(params.integrator);
  if (const int n = free_node_count(model); n > kGeneralLimitsNodes)
    return "with dashpot or Rayleigh damping on " + std::to_string(n) + " free nodes (over " +
           std::to_string(kGeneralLimitsNodes) +
           ") it takes minutes; dampbound bounds SCENE computes it";
  return "";
}

const char* to_string(Linearisation at) {
  switch (at) {
    case Linearisation::rest:
      return "rest";
    case Linearisation::state:
      return "state";
    case Linearisation::equilibrium:
      return "equilibrium";
  }
  return "?";
}

std::optional<Linearisation> parse_linearisation(const std::string& text) {
  for (Linearisation at : {Linearisation::rest, Linearisation::state, Linearisation::equilibrium})
    if (text == to_string(at)) return at;
  return std::nullopt;
}

TunerCriteria::~TunerCriteria() {
  wait();
  for (auto& job : retired_) job.wait();
}

/// The static equilibrium's positions (empty where there is none: `f` says why) and Newton's
/// result in f.equilibrium (without its positions).
std::vector<Vec3> TunerCriteria::equilibrium_positions(const Model& model, double factor_budget,
                                                       Finished& f) {
  EquilibriumOptions o;
  o.max_factor_flops = factor_budget;
  try {
    Equilibrium e = static_equilibrium(model, o);
    f.equilibrium_failure = no_equilibrium(e);
    std::vector<Vec3> x = std::move(e.x);
    e.x.clear();
    f.equilibrium = std::move(e);
    if (!f.equilibrium_failure.empty()) x.clear();
    return x;
  } catch (const FactorisationOverBudget& over) {
    f.equilibrium_failure = equilibrium_over_budget(over);
  } catch (const std::exception& e) {
    f.equilibrium_failure = e.what();
  }
  return {};
}

void TunerCriteria::set_linearisation(Linearisation at) {
  if (at == at_) return;
  at_ = at;
  have_key_ = false;  // recompute at the next call, unthrottled
  last_seconds_ = 0;
}

void TunerCriteria::set_factor_budget(double flops) {
  if (flops == factor_budget_) return;
  factor_budget_ = flops;
  have_key_ = false;  // recompute at the next call, unthrottled
  last_seconds_ = 0;
}

void TunerCriteria::forget() {
  if (job_.valid()) retired_.push_back(std::move(job_));  // joined later, never by a frame
  results_.clear();
  exact_.reset();
  rest_net_.reset();
  equilibrium_.reset();
  equilibrium_failure_.clear();
  have_key_ = false;
  rows_valid_ = false;
  exact_iteration_ = rows_iteration_ = 0;
  ++exact_version_;
}

void TunerCriteria::wait() {
  if (job_.valid()) job_.wait();
  collect();
}

void TunerCriteria::collect() {
  retired_.erase(std::remove_if(retired_.begin(), retired_.end(),
                                [](const std::future<Finished>& job) {
                                  return job.wait_for(std::chrono::seconds(0)) ==
                                         std::future_status::ready;
                                }),
                 retired_.end());
  if (!job_.valid() || job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
  Finished f = job_.get();
  last_seconds_ = f.seconds;
  // A result of another mode (switched while it ran) is dropped; the next call starts anew.
  if (f.at != at_) return;
  exact_ = std::move(f.exact);
  rest_net_ = f.rest_net;
  equilibrium_ = std::move(f.equilibrium);
  equilibrium_failure_ = std::move(f.equilibrium_failure);
  ++exact_version_;
  exact_iteration_ = f.iteration;
  exact_shown_at_ = f.at;
}

const ExactStability* TunerCriteria::exact(const Session& s, std::uint64_t topology,
                                           std::uint64_t state) {
  collect();
  // Every analysis runs on the worker thread. The frame that starts one at rest on a small
  // mesh without SPEC 10's damping (tens of ms at the paper's 1296 nodes, once per change)
  // waits for it at most frame_wait: the window's 50 ms show the new result in the same frame
  // there and hold no frame longer (stiff-region's first analysis took 1.3 s in the frame);
  // tests and scripted runs wait to the end. Larger meshes, SPEC 10's limits, the analysis
  // that follows the state and the one at the equilibrium are never waited for.
  const bool following = at_ == Linearisation::state;
  const bool waited = at_ == Linearisation::rest && free_node_count(s.model()) <= worker_nodes_ &&
                      !other_damping(s.params());
  const double now = seconds_now();
  const bool moved = following && state != state_;
  const bool changed = !have_key_ || topology != topology_ || !same_key(key_, s.params()) || moved;
  // On a large mesh the analysis takes long: while a slider is dragged (or the run goes on,
  // when it follows the state), keep the last result and recompute at most every few
  // durations, so the window stays responsive. An analysis the frame waits for is never
  // held back: the wait is bounded (frame_wait) and one job runs at a time, and a frame that
  // waits must show its own parameters' analysis (under a sanitizer the 6 x 6 plane's took
  // over 50 ms and the next change was shown the last one's limits).
  const double slow = last_seconds_ > slow_threshold_ ? 4 * last_seconds_ : 0.0;
  const double interval = following ? std::max(follow_interval_, slow) : slow;
  const bool throttled =
      !waited && have_key_ && (exact_ || job_.valid()) && now - last_time_ < interval;
  // Cancelled: not again for the same parameters and springs (a move of the state aside).
  if (cancelled_ && have_key_ && topology == topology_ && same_key(key_, s.params()))
    return exact_ ? &*exact_ : nullptr;
  cancelled_ = false;
  if (!changed || throttled || job_.valid()) return exact_ ? &*exact_ : nullptr;
  last_time_ = now;
  have_key_ = true;
  topology_ = topology;
  state_ = state;
  key_ = s.params();
  ++exact_runs_;
  {
    // On a worker thread; past frame_wait the last result stays on show (computing() says a
    // new one is on its way). The worker shares the session's model (no copy: a parameter
    // change copies it only while the worker still holds it) and copies only the positions it
    // follows.
    const int iteration = following ? s.state().iteration : 0;
    std::vector<Vec3> x = following ? s.state().x : std::vector<Vec3>{};
    const std::string what = other_damping(s.params())
                                 ? "the general damping matrix's limits (SPEC 10: a few "
                                   "factorisations per limit)"
                                 : "the exact linear analysis (SPEC 7)";
    stage_ = (at_ == Linearisation::equilibrium ? "Newton's method to the static equilibrium, "
                                                  "then " + what
              : at_ == Linearisation::state ? what + " at iteration " + std::to_string(iteration)
                                            : what + " at rest") +
             " on " + std::to_string(free_node_count(s.model())) + " free nodes";
    job_ = std::async(
        std::launch::async, [model = s.shared_model(), x = std::move(x), params = s.params(),
                             iteration, at = at_, budget = factor_budget_, shared = shared_] {
          const double t0 = seconds_now();
          Finished f;
          f.iteration = iteration;
          f.at = at;
          if (at == Linearisation::equilibrium) {
            std::vector<Vec3> held = equilibrium_positions(*model, budget, f);
            if (!held.empty()) f.exact = analyse(*model, held, params, budget, shared);
          } else {
            f.exact = analyse(*model, at == Linearisation::state ? x : model->spec().rest, params,
                              budget, shared);
          }
          if (at == Linearisation::rest) f.rest_net = net_force(*model, model->spec().rest);
          f.seconds = seconds_now() - t0;
          return f;
        });
  }
  if (waited && frame_wait_ > 0) {
    if (std::isinf(frame_wait_))
      job_.wait();
    else
      job_.wait_for(std::chrono::duration<double>(frame_wait_));
    collect();
  }
  return exact_ ? &*exact_ : nullptr;
}

double TunerCriteria::computing_seconds() const {
  return job_.valid() ? seconds_now() - last_time_ : 0.0;
}

void TunerCriteria::cancel() {
  if (!job_.valid()) return;
  retired_.push_back(std::move(job_));  // joined later, never by a frame
  job_ = {};
  cancelled_ = true;
}

const std::vector<CriterionResult>& TunerCriteria::evaluate(const Session& s,
                                                            std::uint64_t topology,
                                                            std::uint64_t state) {
  const ExactStability* e = exact(s, topology, state);
  // A large mesh: while only the state moves, the rows are refreshed at most every
  // follow_interval (each takes a pass over the springs: 4.6 ms per frame at 40k nodes).
  const double now = seconds_now();
  const Params& p = s.params();
  const bool same_inputs = rows_valid_ && topology == rows_topology_ && same_key(rows_key_, p) &&
                           rows_key_.policy == p.policy && rows_key_.factor == p.factor &&
                           exact_version_ == rows_exact_version_;
  if (same_inputs && free_node_count(s.model()) > worker_nodes_ &&
      now - rows_time_ < follow_interval_)
    return results_;
  rows_valid_ = true;
  rows_topology_ = topology;
  rows_key_ = p;
  rows_exact_version_ = exact_version_;
  rows_time_ = now;
  rows_iteration_ = s.state().iteration;
  results_.clear();
  try {
    if (e != nullptr) {
      results_ = all_criteria(s.model(), s.state(), s.params(), *e);
    } else {
      results_ = paper_criteria(s.model(), s.state(), s.params());
      const auto classic = classic_criteria(s.model(), s.params());
      results_.insert(results_.end(), classic.begin(), classic.end());
      const auto safe = safe_criteria(s.model(), s.state(), s.params());  // SPEC 9: O(springs)
      results_.insert(results_.end(), safe.begin(), safe.end());
    }
  } catch (const std::exception&) {
    // A state the criteria cannot judge (e.g. after divergence): show what is known.
  }
  return results_;
}

std::optional<double> TunerCriteria::exact_gamma_max(const Session& s, std::uint64_t topology,
                                                     std::uint64_t state) {
  const ExactStability* e = exact(s, topology, state);
  if (e == nullptr || !std::isfinite(e->gamma_hi) || !(e->gamma_hi > 0)) return std::nullopt;
  return e->gamma_hi;
}

void TunerSuggest::start(const Session& session) {
  launch(session.shared_scene(), session.shared_model(), session.state().iteration,
         session.params(), session.rules(), session.springs_cut());
}

void TunerSuggest::start(const SceneSpec& scene, const Params& params, const StopRules& rules,
                         int cut) {
  launch(std::make_shared<const SceneSpec>(scene), nullptr, 0, params, rules, cut);
}

void TunerSuggest::launch(std::shared_ptr<const SceneSpec> shared,
                          std::shared_ptr<const Model> model, int iteration, const Params& params,
                          const StopRules& rules, int cut) {
  job_.launch([shared = std::move(shared), model = std::move(model), iteration, params, rules,
               cut, budget = factor_budget_](JobControl& control) {
    // With a model: the scene as the run has it (Session::current_scene), built here.
    std::optional<SceneSpec> as_run;
    if (model) as_run = scene_as_run(*shared, *model, iteration);
    const SceneSpec& scene = as_run ? *as_run : *shared;
    Suggestion s;
    s.params = params;
    s.springs = scene.model.spring_count();
    s.springs_cut = cut;
    SuggestOptions options;
    options.max_factor_flops = budget;  // over it: what is proved without a factorisation
    std::string part;
    options.progress = [&part, &control](int done, int total, const std::string& next) {
      return control.report(part + ", stage " + std::to_string(done + 1) + " of " +
                            std::to_string(total) + ": " + next);
    };
    part = "damping range";
    s.damping = suggest_damping(scene, params, rules, options);
    part = "time step";
    s.step = suggest_step(scene, params, rules, options);
    return s;
  });
}

Params with_best_gamma(const Params& current, const Suggestion& s) {
  Params p = current;
  if (std::isfinite(s.damping.gamma_best) && s.damping.gamma_best >= 0)
    p.gamma = s.damping.gamma_best;
  return p;
}

Params with_suggested_dt(const Params& current, const Suggestion& s) {
  Params p = current;
  if (std::isfinite(s.step.dt_all) && s.step.dt_all > 0) p.dt = s.step.dt_all;
  return p;
}

}  // namespace dampbound::ui
