// The trial body's flat arrays from a SceneSpec (the same values compile_model() and the
// batched kernel derive), and its host copy, compiled like the rest of core without
// floating-point contraction.
#include "core/sweep/flat_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/physics/integrate.hpp"
#include "core/run/settle_proof.hpp"
#include "core/sweep/detail/trial_body.hpp"
#include "dampbound/physics/model.hpp"

namespace dampbound {

using trial_body::FlatModel;
using trial_body::TrialConsts;

std::optional<std::string> trial_body_unsupported(const SceneSpec& scene) {
  if (!scene.cuts.empty()) return "the scene cuts springs during the run";
  const Integrator in = scene.params.integrator;
  if (!integrator_traits(in).batched_kernel) return std::string("integrator ") + to_string(in);
  return std::nullopt;
}

namespace {

bool all_equal(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [&](double x) { return x == v.front(); });
}

}  // namespace

FlatScene::FlatScene(const SceneSpec& scene, DampingPolicy policy, const StopRules& rules)
    : base_(scene.params) {
  if (const auto why = trial_body_unsupported(scene))
    throw std::invalid_argument("trial body: " + *why);
  const ModelSpec& mo = scene.model;
  const size_t n = mo.rest.size();
  const State s0 = initial_state(scene);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      rest_.push_back(mo.rest[i][c]);
      x0_.push_back(s0.x[i][c]);
      v0_.push_back(s0.v[i][c]);
      ext_.push_back(mo.external_force[i][c]);
    }
  anchor_scale_ = mo.anchor_scale;
  anchor_kd_scale_ = mo.anchor_kd_scale.empty() ? std::vector<double>(n, 1.0) : mo.anchor_kd_scale;
  mass_scale_ = mo.mass_scale;
  gamma_scale_ = mo.gamma_scale;
  fixed_ = mo.fixed;
  // kappa_i of eq. 5 = kappa * (largest incident scale): x -> kappa*x rounds monotonically.
  kappa_max_scale_ = anchor_scale_;
  for (const Spring& sp : mo.springs) {
    spring_i_.push_back(sp.i);
    spring_j_.push_back(sp.j);
    rest_length_.push_back(sp.rest_length);
    kappa_scale_.push_back(sp.kappa_scale);
    kd_scale_.push_back(sp.kd_scale);
    for (int e : {sp.i, sp.j}) {
      double& k = kappa_max_scale_[static_cast<size_t>(e)];
      k = std::max(k, sp.kappa_scale);
    }
  }
  const Model model = compile_model(mo, scene.params);
  incident_offset_ = model.incident_offset;
  incident_ = model.incident;
  shape_.nodes = static_cast<int>(n);
  shape_.springs = static_cast<int>(mo.springs.size());
  shape_.policy = policy;
  shape_.semi_implicit = scene.params.integrator == Integrator::semi_implicit_euler;
  shape_.uniform =
      n > 0 && all_equal(mass_scale_) && all_equal(gamma_scale_) && all_equal(kappa_max_scale_);
  shape_.rules = rules;
  if (rules.rule == StopRule::settled)
    shape_.settle = settle_scene_bound(mo, x0_, v0_, scene.params.integrator, policy, false,
                                       !scene.cuts.empty());
}

FlatModel FlatScene::view() const {
  FlatModel m = shape_;
  m.spring_i = spring_i_.data();
  m.spring_j = spring_j_.data();
  m.rest_length = rest_length_.data();
  m.kappa_scale = kappa_scale_.data();
  m.kd_scale = kd_scale_.data();
  m.incident_offset = incident_offset_.data();
  m.incident = incident_.data();
  m.rest = rest_.data();
  m.x0 = x0_.data();
  m.v0 = v0_.data();
  m.ext = ext_.data();
  m.anchor_scale = anchor_scale_.data();
  m.anchor_kd_scale = anchor_kd_scale_.data();
  m.mass_scale = mass_scale_.data();
  m.gamma_scale = gamma_scale_.data();
  m.kappa_max_scale = kappa_max_scale_.data();
  m.fixed = fixed_.data();
  return m;
}

TrialConsts FlatScene::constants(const TrialParams& t) const {
  TrialConsts p;
  p.m = t.m;
  p.kappa = t.kappa;
  p.gamma = t.gamma;
  p.dt = t.dt;
  p.factor = t.factor;
  p.kd = t.kd.value_or(base_.kd);
  p.alpha = t.rayleigh_mass.value_or(base_.rayleigh_mass);
  p.beta = t.rayleigh_stiffness.value_or(base_.rayleigh_stiffness);
  // compile_model()'s spring_damping: some dashpot non-zero, or Rayleigh damping.
  bool dashpots = false;
  for (size_t i = 0; i < anchor_scale_.size() && !dashpots; ++i)
    dashpots = (anchor_scale_[i] > 0 ? p.kd * anchor_kd_scale_[i] : 0.0) != 0;
  for (size_t k = 0; k < kd_scale_.size() && !dashpots; ++k) dashpots = p.kd * kd_scale_[k] != 0;
  p.damped = dashpots || p.alpha != 0 || p.beta != 0;
  if (!fixed_.empty()) {
    // compile_model() and upper_bound(): m_i, m_i/dt, 2 sqrt(m_i kappa_i), gamma_i of node 0.
    p.mass = t.m * mass_scale_[0];
    p.md = p.mass / t.dt;
    p.lo = 2.0 * std::sqrt(p.mass * (t.kappa * kappa_max_scale_[0]));
    p.gu = t.gamma * gamma_scale_[0];
  }
  return p;
}

std::size_t FlatScene::state_doubles() const {
  return (4 * 3 + trial_body::kSafePerNode) * fixed_.size();
}

std::vector<TrialResult> run_trial_body(const FlatScene& scene,
                                        const std::vector<TrialParams>& trials) {
  const FlatModel m = scene.view();
  const size_t n = static_cast<size_t>(scene.nodes());
  std::vector<double> state(scene.state_doubles());
  const trial_body::TrialView view{state.data(),          state.data() + 3 * n,
                                   state.data() + 6 * n,  state.data() + 9 * n,
                                   state.data() + 12 * n, 1};
  std::vector<TrialResult> out;
  out.reserve(trials.size());
  for (const TrialParams& t : trials) {
    trial_body::TrialSlot slot;
    slot.p = scene.constants(t);
    trial_body::trial_begin(m, slot, view);
    while (!trial_body::trial_advance(m, slot, view, 1 << 20)) {
    }
    out.push_back(slot.r);
  }
  return out;
}

}  // namespace dampbound
