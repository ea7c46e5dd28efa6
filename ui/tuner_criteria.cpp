#include "ui/tuner_criteria.hpp"

#include <chrono>
#include <cmath>
#include <exception>

namespace dampbound::ui {

namespace {
bool same_key(const Params& a, const Params& b) {
  return a.m == b.m && a.kappa == b.kappa && a.gamma == b.gamma && a.dt == b.dt &&
         a.integrator == b.integrator;
}

/// gamma_i / m_i equal at every free node: the exact radius is a cheap per-mode formula.
bool uniform_rate(const Model& m) {
  double r0 = -1;
  for (size_t i = 0; i < m.mass.size(); ++i) {
    if (m.fixed[i]) continue;
    const double r = m.gamma[i] / m.mass[i];
    if (r0 < 0) r0 = r;
    if (std::abs(r - r0) > 1e-12 * std::max(r0, 1e-300)) return false;
  }
  return true;
}
}  // namespace

const ExactStability* TunerCriteria::exact(const Session& s, std::uint64_t topology) {
  using Clock = std::chrono::steady_clock;
  const double now = std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
  const bool changed = !have_key_ || topology != topology_ || !same_key(key_, s.params());
  // On a large mesh the analysis takes long: while a slider is dragged, keep the last result
  // and recompute at most every few durations, so the window stays responsive.
  const bool throttled = exact_ && last_seconds_ > 0.01 && now - last_time_ < 4 * last_seconds_;
  if (changed && !throttled) {
    last_time_ = now;
    have_key_ = true;
    topology_ = topology;
    key_ = s.params();
    exact_.reset();
    ++exact_runs_;
    try {
      ExactOptions o;
      o.with_radius = uniform_rate(s.model());  // Arnoldi on a non-uniform mesh can take seconds
      exact_ = exact_stability(s.model(), s.model().rest, s.params(), o);
    } catch (const std::exception&) {
      exact_.reset();
    }
    const double end = std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
    last_seconds_ = end - now;
  }
  return exact_ ? &*exact_ : nullptr;
}

const std::vector<CriterionResult>& TunerCriteria::evaluate(const Session& s,
                                                            std::uint64_t topology) {
  results_.clear();
  const ExactStability* e = exact(s, topology);
  try {
    if (e != nullptr) {
      results_ = all_criteria(s.model(), s.state(), s.params(), *e);
    } else {
      results_ = paper_criteria(s.model(), s.state(), s.params());
      const auto classic = classic_criteria(s.model(), s.params());
      results_.insert(results_.end(), classic.begin(), classic.end());
    }
  } catch (const std::exception&) {
    // A state the criteria cannot judge (e.g. after divergence): show what is known.
  }
  return results_;
}

std::optional<double> TunerCriteria::exact_gamma_max(const Session& s, std::uint64_t topology) {
  const ExactStability* e = exact(s, topology);
  if (e == nullptr || !std::isfinite(e->gamma_hi) || !(e->gamma_hi > 0)) return std::nullopt;
  return e->gamma_hi;
}

TunerSuggest::~TunerSuggest() {
  wait();
}

void TunerSuggest::start(const SceneSpec& scene, const Params& params, const StopRules& rules) {
  if (busy()) return;
  error_.clear();
  pending_ = std::async(std::launch::async, [scene, params, rules] {
    Suggestion s;
    s.params = params;
    s.damping = suggest_damping(scene, params, rules);
    s.step = suggest_step(scene, params, rules);
    return s;
  });
}

bool TunerSuggest::poll() {
  if (!busy()) return false;
  if (pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
  try {
    result_ = pending_.get();
  } catch (const std::exception& e) {
    error_ = e.what();
    result_.reset();
  }
  return true;
}

void TunerSuggest::wait() {
  if (busy()) pending_.wait();
  poll();
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
