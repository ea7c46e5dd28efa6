#include "dampbound/run/session.hpp"

#include <atomic>
#include <stdexcept>
#include <utility>

#include "core/run/settle_proof.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

Session::Session(SceneSpec scene, const Params& params, const StopRules& rules)
    : scene_(std::make_shared<const SceneSpec>(std::move(scene))),
      params_(params),
      rules_(rules) {
  if (const auto why = validate(*scene_)) throw InputError("scene: " + *why);
  if (const auto why = validate(params)) throw InputError(*why);
  if (const auto why = validate(rules)) throw InputError(*why);
  watched_ = scene_->watched;
  reset();
}

std::optional<std::string> validate(const StopRules& r) {
  if (r.max_iterations < 1 || r.max_iterations > 100000000)
    return std::string("max_iterations must be in 1..100000000");
  const struct {
    const char* name;
    double value;
  } numbers[] = {{"reference", r.reference},
                 {"restore_fraction", r.restore_fraction},
                 {"diverge_factor", r.diverge_factor}};
  for (const auto& n : numbers)
    if (const auto why = number_problem(n.value, false)) return std::string(n.name) + " " + *why;
  return std::nullopt;
}

Session::Session(SceneSpec scene) : Session(scene, scene.params, scene.rules) {}

const StepSample& Session::step_once() {
  for (const CutEvent& c : scene_->cuts)
    if (c.iteration == state_.iteration) cut(springs_crossing(*model_, state_.x, c.from, c.to));
  StepSample sample;
  static_cast<StepStats&>(sample) = step(*model_, params_, state_, ws_);
  sample.watched = sample_node(*model_, state_, ws_, watched_);
  if (keep_trace_ || trace_.empty())
    trace_.push_back(sample);
  else
    trace_.back() = sample;
  accumulate(result_, sample, rules_);
  if (settle_ && result_.outcome == Outcome::running && result_.below_since > 0) {
    // SPEC 8: stop early where the proof covers the state (core/run/detail/settle_bound.hpp).
    const SettleProof& proof = *settle_;
    const settle::TrialBound t =
        proof.trial(params_.m, params_.kappa, params_.gamma, params_.dt, rules_);
    const auto& x = state_.x;
    const auto& v = state_.v;
    result_.outcome = settle::early_verdict(
        rules_, result_.outcome, result_.below_since, result_.iterations,
        result_.max_displacement, t, settle_next_, [&] {
          return settle::norm_bound(
              proof.arrays(), t, [&](int i, int c) { return x[static_cast<size_t>(i)][c]; },
              [&](int i, int c) { return v[static_cast<size_t>(i)][c]; });
        });
    if (result_.outcome == Outcome::settled) result_.settled_at = result_.below_since;
  }
  return trace_.back();
}

void Session::set_early_stop(bool on) {
  early_stop_ = on;
  rebuild_settle();
}

void Session::rebuild_settle() {
  settle_.reset();
  if (!early_stop_ || !settle_proof_enabled() || params_.zeta) return;
  const State s0 = initial_state(*scene_);
  std::vector<double> x0, v0;
  for (size_t i = 0; i < s0.x.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      x0.push_back(s0.x[i][c]);
      v0.push_back(s0.v[i][c]);
    }
  auto proof = std::make_shared<SettleProof>(model_->spec(), x0, v0, params_.integrator,
                                             params_.policy, model_->spring_damping,
                                             !scene_->cuts.empty());
  if (!proof->why_not()) settle_ = std::move(proof);
}

const RunResult& Session::run_to_end(const StepObserver& on_step) {
  while (running()) {
    const StepSample& st = step_once();
    if (on_step) on_step(st);
  }
  return result_;
}

void Session::set_params(const Params& params) {
  if (const auto why = validate(params)) throw InputError(*why);
  params_ = params;
  // Copy on write: a worker may be reading a shared_model() snapshot. The count is only ever
  // raised on this thread; a holder that let go released its reads with its decrement, which
  // the fence acquires before the model is written.
  if (model_.use_count() > 1)
    model_ = std::make_shared<Model>(*model_);
  else
    std::atomic_thread_fence(std::memory_order_acquire);
  reparameterise(*model_, params_);
  rebuild_settle();
}

void Session::set_watched(int node) {
  if (node < 0 || node >= model_->spec().node_count()) throw std::out_of_range("watched node");
  watched_ = node;
}

void Session::reset() {
  model_ = std::make_shared<Model>(compile_model(scene_->model, params_));
  state_ = initial_state(*scene_);
  trace_.clear();
  result_ = RunResult{};
  springs_cut_ = 0;
  // The last step's per-node results go with it: at iteration 0 no step has run, as in a new
  // session (the tuner's colours and status, a .vtu of iteration 0, read them as none yet).
  for (auto* v : {&ws_.upper_bound, &ws_.gamma_eff, &ws_.safe_row_sum, &ws_.safe_bound}) v->clear();
  ws_.status.clear();
  settle_next_ = 0;
  rebuild_settle();
}

void Session::perturb() {
  for (const Perturbation& p : scene_->perturbations) {
    state_.x[static_cast<size_t>(p.node)] += p.displacement;
    state_.v[static_cast<size_t>(p.node)] += p.velocity;
  }
}

void Session::displace(int node, const Vec3& offset) {
  if (node < 0 || node >= model_->spec().node_count()) throw std::out_of_range("node");
  if (!model_->spec().fixed[static_cast<size_t>(node)]) state_.x[static_cast<size_t>(node)] += offset;
}

SceneSpec scene_as_run(const SceneSpec& scene, const ModelSpec& model, int iteration) {
  SceneSpec s;
  s.model = model;  // the topology as cut so far (a Model gives its spec, without parameters)
  // Everything but the model and the cuts, as loaded, without copying the loaded mesh.
  s.name = scene.name;
  s.description = scene.description;
  s.path = scene.path;
  s.grid = scene.grid;
  s.params = scene.params;
  s.rules = scene.rules;
  s.perturbations = scene.perturbations;
  s.watched = scene.watched;
  s.runs = scene.runs;
  s.expectations = scene.expectations;
  s.body = scene.body;
  s.regions = scene.regions;
  // step_once applies a cut due at iteration k before the step that leaves iteration k.
  for (const CutEvent& c : scene.cuts)
    if (c.iteration >= iteration) s.cuts.push_back(c);
  return s;
}

SceneSpec Session::current_scene() const {
  return scene_as_run(*scene_, *model_, state_.iteration);
}

int Session::cut(const std::vector<int>& springs) {
  const int before = model_->spec().spring_count();
  model_ = std::make_shared<Model>(compile_model(without_springs(*model_, springs), params_));
  const int removed = before - model_->spec().spring_count();
  springs_cut_ += removed;
  rebuild_settle();
  return removed;
}

}  // namespace dampbound
