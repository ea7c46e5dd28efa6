#include "core/analysis/suggest.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "core/io/format.hpp"
#include "core/physics/detail/numbers.hpp"
#include "core/physics/integrate.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The score of a trial run (settled rule): settled runs by their settled iteration, then the
/// runs that did not settle by their final displacement, then the diverged by how far they got.
std::tuple<int, int, double> score(const RunResult& r) {
  if (r.outcome == Outcome::settled) return {0, r.settled_at, 0.0};
  if (r.outcome == Outcome::not_settled) return {1, 0, r.max_displacement};
  return {2, -r.iterations, 0.0};  // diverged: later is less bad
}

/// Minimises f on [lo, hi] by 400 samples, then golden section between the best sample's
/// neighbours (f need not be unimodal on the whole interval).
template <class F>
double minimise(F f, double lo, double hi) {
  const int n = 400;
  int best = 0;
  double fbest = kInf;
  for (int k = 0; k <= n; ++k) {
    const double v = f(lo + (hi - lo) * k / n);
    if (v < fbest) fbest = v, best = k;
  }
  double a = lo + (hi - lo) * std::max(0, best - 1) / n, b = lo + (hi - lo) * std::min(n, best + 1) / n;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int k = 0; k < 80; ++k) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    (f(c) <= f(d) ? b : a) = (f(c) <= f(d) ? d : c);
  }
  const double mid = 0.5 * (a + b);
  return f(mid) <= fbest ? mid : lo + (hi - lo) * best / n;
}

Params with_gamma(Params p, double gamma) {
  p.gamma = gamma;
  return p;
}

Params with_dt(Params p, double dt) {
  p.dt = dt;
  return p;
}

/// The exact analysis the suggestions start from; over the factorisation budget, with what
/// is proved without one (ExactStability::unfactored).
ExactStability exact_limits(const Model& model, const Params& params,
                            const SuggestOptions& options) {
  ExactOptions o;
  o.with_radius = false;
  o.threads = options.threads;
  o.max_factor_flops = options.max_factor_flops;
  o.shared = options.shared;
  return exact_stability(model, model.spec().rest, params, o);
}

/// Over the budget with nothing proved stable: nothing to suggest.
[[noreturn]] void nothing_proved(const ExactStability& e, const char* what) {
  throw std::runtime_error("suggest needs the exact limits or a " + std::string(what) +
                           " proved stable without them, and " + e.over_budget_reason() +
                           "; bounds shows what is proved");
}

/// The largest dt known stable at the analysed gamma: the exact limit, or over the budget
/// the largest proved (NaN where none).
double stable_dt(const ExactStability& e) {
  if (e.computed()) return e.dt_max;
  return e.unfactored.unconditional ? kInf : e.unfactored.dt_stable_up_to;
}

/// SuggestOptions::progress, stage by stage: the call's count of stages and the next one.
class Stages {
 public:
  Stages(const SuggestOptions& options, int total) : options_(options), total_(total) {}
  void add(int more) { total_ += more; }
  void next(const std::string& what) {
    if (options_.progress && !options_.progress(done_, total_, what)) throw SuggestCancelled();
    ++done_;
  }

 private:
  const SuggestOptions& options_;
  int done_ = 0, total_;
};

}  // namespace

VerifiedRun verify_run(const SceneSpec& scene, const Params& params, const StopRules& rules,
                       const std::string& label) {
  StopRules settled = rules;
  settled.rule = StopRule::settled;
  Session session(scene, params, settled);
  return {label, params, session.run_to_end(), settled};
}

DampingSuggestion suggest_damping(const SceneSpec& scene, const Params& params_in,
                                  const StopRules& rules, const SuggestOptions& options) {
  Params params = params_in;
  params.policy = DampingPolicy::fixed;
  DampingSuggestion s;
  s.dt = params.dt;
  Stages stages(options, 1 + (options.verify ? 3 : 0));
  stages.next("exact limits at this dt");
  const Model model = compile_model(scene.model, params);
  s.exact = exact_limits(model, params, options);

  // Eq. 5 at every free node: gamma * gamma_scale_i >= 2 sqrt(m_i kappa_i) (SPEC 3).
  double eq5 = 0, unit_rate_max = 0;
  const NodeSafeBounds rows(model, model.spec().rest);  // SPEC 9 (10 with C') at rest
  s.safe_max = kInf;
  std::map<std::tuple<double, double, double>, NodeClass> classes;
  for (size_t i = 0; i < model.spec().rest.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const double lo = model.lower_bound[i], sc = model.spec().gamma_scale[i];
    eq5 = std::max(eq5, sc > 0 ? lo / sc : (lo > 0 ? kInf : 0.0));
    unit_rate_max = std::max(unit_rate_max, sc / model.mass[i]);
    NodeClass& c = classes[{model.mass[i], model.node_kappa[i], sc}];
    const double safe = rows.gamma_safe(static_cast<int>(i), params.dt);
    const double dt_safe = rows.dt_safe(static_cast<int>(i), lo);
    s.safe_max = std::min(s.safe_max, safe_user_gamma(safe, sc));
    if (c.count == 0 || safe < c.safe_max) c.safe_max = safe;
    if (c.count == 0 || dt_safe < c.dt_safe) c.dt_safe = dt_safe;
    if (c.count++ == 0) {
      c.example = static_cast<int>(i);
      c.mass = model.mass[i];
      c.kappa = model.node_kappa[i];
      c.gamma_scale = sc;
      c.lower_bound = lo;
    }
  }
  double lo = s.exact.gamma_lo, upper = s.exact.gamma_hi;
  std::string lo_by = std::string("exact lower limit (") + to_string(params.integrator) + ")";
  s.max_by = std::string("exact upper limit (") + to_string(params.integrator) + ")" +
             (s.exact.method == ExactMethod::frozen_estimate ? ", frozen-rate estimate" : "");
  if (!s.exact.computed()) {  // what is proved stable without a factorisation
    const ExactStability::Unfactored& u = s.exact.unfactored;
    s.proved_only = true;
    lo_by = "proved stable without a factorisation";
    if (u.unconditional) {  // implicit Euler with K >= 0 proved: every gamma and dt
      lo = 0;
      upper = kInf;
      s.max_by = "proved stable without a factorisation: implicit Euler with K >= 0 (the safe "
                 "bound's floor) is stable for every gamma and dt";
    } else {
      if (!(u.gamma_stable_lo <= u.gamma_stable_hi)) nothing_proved(s.exact, "damping range");
      lo = u.gamma_stable_lo;
      upper = u.gamma_stable_hi;
      s.max_by = integrator_traits(params.integrator).paper_step
                     ? "proved stable without a factorisation: Gershgorin on the exact index "
                       "matrix, included"
                     : "proved stable without a factorisation: every mode in [0, Gershgorin's "
                       "bound], included";
    }
    s.gamma_unstable_from = u.gamma_unstable_from;
  }
  s.gamma_min = std::max(eq5, lo);
  s.min_by = eq5 >= lo ? "paper eq. 5 (lower bound)" : lo_by;
  s.gamma_max = upper;
  s.empty = s.proved_only ? !(s.gamma_min <= s.gamma_max) : !(s.gamma_min < s.gamma_max);
  for (auto& [key, c] : classes) {
    c.gamma_min = s.gamma_min * c.gamma_scale;
    c.gamma_max = s.gamma_max * c.gamma_scale;
    s.classes.push_back(c);
  }
  s.dt_only = classic_criteria(model, params);
  for (const auto& c : s.dt_only) s.dt_accepted = s.dt_accepted && c.verdict == CriterionVerdict::within;

  if (s.empty) {
    if (std::isfinite(s.gamma_min)) {
      const Params p = with_gamma(params, s.gamma_min);
      const Model m = compile_model(scene.model, p);
      s.dt_max_at_gamma_min = stable_dt(exact_limits(m, p, options));
    }
    s.gamma_best = kNaN;
    s.best_rho = kNaN;
    return s;
  }
  // The search interval: up to the exact limit, or where no limit exists, to four times the
  // critical damping of the stiffest mode (beyond it every mode is overdamped and slower).
  // Over the budget the spectrum is known to lie in [SPEC 9's floor, Gershgorin's bound].
  StiffnessSpectrum spectrum = s.exact.decaying;
  if (s.proved_only) {
    const std::optional<double> floor = psd_floor(model, model.spec().rest);
    spectrum = {floor ? std::max(*floor, 0.0) : 0.0, s.exact.unfactored.lambda_max_hi};
  }
  double hi = s.gamma_max;
  if (!std::isfinite(hi)) {
    const double crit = 2 * std::sqrt(std::max(spectrum.lambda_max, 0.0));  // c, 1/s
    hi = s.gamma_min + 4 * crit / std::max(unit_rate_max, 1e-300);
  }
  hi = s.gamma_min + (hi - s.gamma_min) * (1 - 1e-9);  // stay inside the open end
  // With dashpot or Rayleigh damping (SPEC 10) the nodal per-mode radius does not describe
  // the step: trial runs decide, as for non-uniform rates.
  const bool uniform_rate = s.exact.uniform_rate && !s.exact.spec10;
  if (s.proved_only && uniform_rate && !(spectrum.lambda_min > 0)) {
    // The slowest mode decides the settling, and only lambda_min >= 0 is proved: at
    // lambda = 0 the radius is 1 for every gamma.
    s.gamma_best = kNaN;
    s.best_rho = kNaN;
    s.best_method = "not computed: over the budget only lambda_min >= 0 is proved (the safe "
                    "bound's floor), and the slowest mode decides";
  } else if (uniform_rate) {
    // Exact: rho(gamma) is the max over the modes' 2x2 amplification matrices; the rate per
    // unit gamma is that of any free node (uniform_rate: all free nodes share it).
    double rate = 0;
    for (size_t i = 0; i < model.spec().rest.size(); ++i)
      if (!model.spec().fixed[i]) {
        rate = model.spec().gamma_scale[i] / model.mass[i];
        break;
      }
    auto rho_free = [&](double g) {
      return spectrum_spectral_radius(params.integrator, spectrum, g * rate, params.dt);
    };
    s.gamma_best = minimise(rho_free, s.gamma_min, hi);
    s.best_rho = rho_free(s.gamma_best);
    s.best_method =
        s.proved_only
            ? "minimum over the range of the largest radius of any lambda in [" +
                  format_human(spectrum.lambda_min) + ", " +
                  format_human(spectrum.lambda_max) +
                  "] (the safe bound's floor, Gershgorin's bound: the spectrum lies inside" +
                  (integrator_traits(params.integrator).euler_velocity_update
                       ? ", and the interval's ends decide, so rho is at most this)"
                       : "; the largest radius of 65 lambdas sampled in it)")
            : "minimum spectral radius of the step over the range (per-mode, exact)";
  } else {
    // Non-uniform rates or SPEC 10 damping: trial runs of the scene's protocol; fewest
    // iterations to settle wins.
    const int n = std::max(2, options.trials);
    stages.add(n + 9);
    auto best_of = [&](double a, double b, int count, double& best_gamma, RunResult& best_run) {
      for (int k = 0; k < count; ++k) {
        const double g = a + (b - a) * k / (count - 1);
        stages.next("trial run for the fastest-settling gamma");
        const RunResult r = verify_run(scene, with_gamma(params, g), rules, "").result;
        if (best_gamma < 0 || score(r) < score(best_run)) best_gamma = g, best_run = r;
      }
    };
    double g = -1;
    RunResult r;
    best_of(s.gamma_min, hi, n, g, r);
    const double step = (hi - s.gamma_min) / (n - 1);
    best_of(std::max(s.gamma_min, g - step), std::min(hi, g + step), 9, g, r);
    s.gamma_best = g;
    s.best_rho = kNaN;
    s.best_method = "earliest settled iteration over " + std::to_string(n + 9) +
                    " trial runs of the scene (" +
                    (s.exact.spec10 ? std::string("dashpot or Rayleigh damping")
                                    : std::string("rates gamma_i/m_i are not uniform")) +
                    ")";
  }
  if (options.verify) {
    if (std::isfinite(s.gamma_best)) {
      stages.next("verifying the fastest-settling gamma");
      s.runs.push_back(verify_run(scene, with_gamma(params, s.gamma_best), rules, "fastest-settling gamma"));
    }
    stages.next("verifying the lower end of the range");
    s.runs.push_back(verify_run(scene, with_gamma(params, s.gamma_min), rules, "lower end of the range"));
    if (std::isfinite(s.gamma_max)) {
      stages.next("verifying 99% of the way to the upper end");
      s.runs.push_back(verify_run(scene, with_gamma(params, s.gamma_min + 0.99 * (s.gamma_max - s.gamma_min)),
                                  rules, "99% of the way to the upper end"));
    }
  }
  return s;
}

StepSuggestion suggest_step(const SceneSpec& scene, const Params& params_in, const StopRules& rules,
                            const SuggestOptions& options) {
  Params params = params_in;
  params.policy = DampingPolicy::fixed;
  StepSuggestion s;
  s.gamma = params.gamma;
  Stages stages(options, 1 + (options.verify ? 2 : 0));
  stages.next("exact limits at this gamma");
  const Model model = compile_model(scene.model, params);
  s.exact = exact_limits(model, params, options);
  s.dt_exact = s.exact.dt_max;
  s.dt_all_by = std::string("exact limit (") + to_string(params.integrator) + ")";
  if (!s.exact.computed()) {  // the largest dt proved stable without a factorisation
    s.proved_only = true;
    s.dt_exact = stable_dt(s.exact);
    s.dt_unstable_from = s.exact.unfactored.dt_unstable_from;
    if (!(s.dt_exact > 0)) nothing_proved(s.exact, "time step");
    s.dt_all_by = "proved stable without a factorisation";
  }
  s.dt_all = s.dt_exact;
  {  // SPEC 9 at rest: the smallest dt_safe_i at the user's gamma_i
    const NodeSafeBounds safe(model, model.spec().rest);
    s.dt_safe = kInf;
    for (size_t i = 0; i < model.mass.size(); ++i) {
      if (model.spec().fixed[i]) continue;
      const double h = safe.dt_safe(static_cast<int>(i), model.gamma[i]);
      if (h < s.dt_safe) s.dt_safe = h, s.dt_safe_node = static_cast<int>(i);
    }
  }
  // The dt-only criteria, inverted for dt (their values do not depend on dt except k_c).
  double m_total = 0, kappa_max = 0;
  int n = 0;
  for (const CriterionResult& c : classic_criteria(model, params)) {
    if (c.name.rfind("Provot", 0) == 0 && c.value < s.dt_all) s.dt_all = c.value, s.dt_all_by = c.name;
    if (c.name.rfind("Kacic", 0) == 0 && c.value < s.dt_all) s.dt_all = c.value, s.dt_all_by = c.name;
  }
  for (size_t i = 0; i < model.spec().rest.size(); ++i)
    if (!model.spec().fixed[i]) m_total += model.mass[i], ++n, kappa_max = std::max(kappa_max, model.node_kappa[i]);
  if (n > 0 && kappa_max > 0) {
    // Delingette: kappa_max < m_total / (n pi^2 dt^2)  <=>  dt < sqrt(m_total / (n pi^2 kappa_max)).
    const double dt_d = std::sqrt(m_total / (n * kPi * kPi * kappa_max));
    if (dt_d < s.dt_all) s.dt_all = dt_d, s.dt_all_by = "Delingette critical stiffness";
  }
  if (options.verify && s.dt_exact > 0) {  // no dt is stable: nothing to run (dt must be > 0)
    if (std::isfinite(s.dt_exact)) {
      stages.next("verifying 99% of the exact dt limit");
      s.runs.push_back(verify_run(scene, with_dt(params, 0.99 * s.dt_exact), rules, "99% of the exact limit"));
    }
    if (std::isfinite(s.dt_all) && !(s.dt_all >= 0.99 * s.dt_exact)) {
      stages.next("verifying the largest dt every criterion accepts");
      s.runs.push_back(verify_run(scene, with_dt(params, s.dt_all), rules, "largest dt every criterion accepts"));
    }
  }
  return s;
}

}  // namespace dampbound
