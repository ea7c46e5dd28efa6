// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/criteria.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "core/analysis/criteria_safe.hpp"
#include "core/analysis/criteria_unfactored.hpp"
#include "core/io/format.hpp"
#include "core/physics/detail/numbers.hpp"
#include "core/physics/integrate.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/forces.hpp"

namespace dampbound {
namespace {

constexpr double kPi = 3.14159265358979323846;

CriterionResult criterion(std::string name, std::string source, std::string formula) {
  CriterionResult c;
  c.name = std::move(name);
  c.source = std::move(source);
  c.formula = std::move(formula);
  return c;
}

/// Per mode, a number taken over the spectrum's certified outer ends and the same over its
/// inner ends (ExactStability::Inner): whether the printed digits tell them apart, so that the
/// row must say its spectrum is only bracketed.
bool bracketed(double outer, double inner) {
  return !std::isnan(outer) && !std::isnan(inner) &&
         format_digits(outer, 8) != format_digits(inner, 8);
}

/// A test where an end of the spectrum is only bracketed: proved where it holds over the outer
/// ends, undecided (n/a) where it holds only over the inner ones, failed where over neither.
CriterionVerdict bracketed_verdict(bool outer_ok, bool inner_ok) {
  return outer_ok   ? CriterionVerdict::within
         : inner_ok ? CriterionVerdict::not_applicable
                    : CriterionVerdict::beyond;
}

/// "[a, b]" of two numbers in either order, 8 digits each.
std::string span(double a, double b) {
  return "[" + format_digits(std::min(a, b), 8) + ", " + format_digits(std::max(a, b), 8) + "]";
}

}  // namespace

const char* to_string(CriterionVerdict v) {
  switch (v) {
    case CriterionVerdict::within: return "within";
    case CriterionVerdict::beyond: return "BEYOND";
    case CriterionVerdict::not_applicable: return "n/a";
  }
  return "?";
}

double delingette_critical_stiffness(double m_total, int n, double dt) {
  return m_total / (n * kPi * kPi * dt * dt);
}

double provot_natural_period(double m, double kappa) { return kPi * std::sqrt(m / kappa); }

double kacic_alesic_dt(double m, double K) { return 2.0 * std::sqrt(m / K); }

std::vector<double> combined_stiffness(const Model& model) {
  std::vector<double> K = model.anchor_kappa;
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    const Spring& s = model.spec().springs[k];
    K[static_cast<size_t>(s.i)] += model.spring_kappa[k];
    K[static_cast<size_t>(s.j)] += model.spring_kappa[k];
  }
  return K;
}

std::vector<CriterionResult> classic_criteria(const Model& model, const Params& params) {
  const double dt = params.dt;
  std::vector<CriterionResult> out;
  double m_total = 0, kappa_max = 0;
  int n = 0;
  for (size_t i = 0; i < model.spec().rest.size(); ++i)
    if (!model.spec().fixed[i]) {
      m_total += model.mass[i];
      ++n;
      kappa_max = std::max(kappa_max, model.node_kappa[i]);
    }
  {
    CriterionResult c = criterion("Delingette critical stiffness", "Delingette 2000 (paper ref. [11])",
                      "k_c = m_total / (n pi^2 dt^2); require kappa < k_c (kappa: the stiffest "
                      "spring or anchor)");
    c.unit = "mass unit/s^2";
    c.value = n ? delingette_critical_stiffness(m_total, n, dt) : kInf;
    c.verdict = verdict_of(kappa_max < c.value);
    c.test = "kappa_max = " + format_human(kappa_max) + (kappa_max < c.value ? " < " : " >= ") +
             "k_c = " + format_human(c.value) + " (n = " + plural(n, "free node") + ")";
    out.push_back(c);
  }
  const std::vector<double> K = combined_stiffness(model);
  CriterionResult provot = criterion("Provot natural period", "Provot 1995 (paper ref. [2])",
                         "T0_i = pi sqrt(m_i / kappa_i), kappa_i = max incident stiffness "
                         "(paper sec. 4); require dt < T0 at every node");
  provot.unit = "s";
  provot.value = kInf;
  CriterionResult ka = criterion("Kacic-Alesic (Verlet) step", "Kacic-Alesic et al. 2003 (paper ref. [12])",
                     "dt_i = 2 sqrt(m_i / K_i), K_i = sum of the stiffness of every spring and "
                     "anchor at i; require dt <= dt_i at every node");
  ka.unit = "s";
  ka.value = kInf;
  for (size_t i = 0; i < model.spec().rest.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const double t0 = model.node_kappa[i] > 0 ? provot_natural_period(model.mass[i], model.node_kappa[i]) : kInf;
    if (t0 < provot.value) provot.value = t0, provot.node = static_cast<int>(i);
    const double tk = K[i] > 0 ? kacic_alesic_dt(model.mass[i], K[i]) : kInf;
    if (tk < ka.value) ka.value = tk, ka.node = static_cast<int>(i);
  }
  provot.verdict = verdict_of(dt < provot.value);
  provot.test = "dt = " + format_human(dt) + (dt < provot.value ? " < " : " >= ") + "T0 = " +
                format_human(provot.value) + " (worst node " + std::to_string(provot.node) + ")";
  ka.verdict = verdict_of(dt <= ka.value);
  ka.test = "dt = " + format_human(dt) + (dt <= ka.value ? " <= " : " > ") + "2 sqrt(m/K) = " +
            format_human(ka.value) + " (worst node " + std::to_string(ka.node) + ")";
  out.push_back(provot);
  out.push_back(ka);
  return out;
}

std::vector<CriterionResult> paper_criteria(const Model& model, const State& state,
                                            const Params& params) {
  std::vector<CriterionResult> out;
  CriterionResult lo = criterion("paper lower bound", "Bhasin & Liu eq. 5",
                     "gamma_i >= gamma_lo_i = 2 sqrt(m_i kappa_i), kappa_i = max incident stiffness");
  lo.unit = "mass unit/s";
  double worst = kInf;
  for (size_t i = 0; i < model.spec().rest.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const double margin = model.gamma[i] - model.lower_bound[i];
    if (margin < worst) worst = margin, lo.node = static_cast<int>(i);
  }
  if (lo.node >= 0) {
    const auto w = static_cast<size_t>(lo.node);
    lo.value = model.lower_bound[w];
    lo.verdict = verdict_of(model.gamma[w] >= lo.value);
    lo.test = "gamma_i = " + format_human(model.gamma[w]) + (model.gamma[w] >= lo.value ? " >= " : " < ") +
              "gamma_lo = " + format_human(lo.value) + " (worst node " + std::to_string(lo.node) + ")";
  }
  out.push_back(lo);

  std::vector<Vec3> force;
  internal_forces(model, state.x, force);
  CriterionResult hi = criterion("paper upper bound", "Bhasin & Liu eq. 6",
                     "gamma_i <= gamma_hi_i = |v_i m_i/dt + F_i| / |v_i| at the state (inf at v_i = 0)");
  hi.unit = "mass unit/s";
  hi.value = kInf;
  CriterionResult check = criterion("paper runtime check", "Bhasin & Liu sec. 5",
                        "node i unstabilisable when gamma_lo_i > gamma_hi_i");
  check.unit = "nodes";
  int unstabilisable = 0, moving = 0;
  worst = kInf;
  for (size_t i = 0; i < model.spec().rest.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const double bound = upper_bound(state.v[i], force[i], model.mass[i], params.dt);
    if (std::isinf(bound)) continue;
    ++moving;
    if (model.lower_bound[i] > bound) {
      if (check.node < 0) check.node = static_cast<int>(i);
      ++unstabilisable;
    }
    if (bound - model.gamma[i] < worst) worst = bound - model.gamma[i], hi.node = static_cast<int>(i), hi.value = bound;
  }
  if (moving == 0) {
    hi.verdict = check.verdict = CriterionVerdict::not_applicable;
    hi.test = "every v_i = 0 (at rest): damping has no effect this step, gamma_hi = inf";
    check.test = "no node moves: nothing to check";
  } else {
    const double g = model.gamma[static_cast<size_t>(hi.node)];
    hi.verdict = verdict_of(g <= hi.value);
    hi.test = "gamma_i = " + format_human(g) + (g <= hi.value ? " <= " : " > ") + "gamma_hi = " +
              format_human(hi.value) + " (worst node " + std::to_string(hi.node) + ")";
    // Eq. 6 comes from the Euler velocity update v' = v + a dt, which the paper's step and
    // forward Euler share; for the other integrators it is shown for reference only.
    if (!integrator_traits(params.integrator).euler_velocity_update)
      hi.test += "; derived for the Euler update, shown for reference";
    check.value = unstabilisable;
    check.verdict = verdict_of(unstabilisable == 0);
    check.test = std::to_string(unstabilisable) + " of " + std::to_string(moving) +
                 " moving nodes unstabilisable";
  }
  out.push_back(hi);
  out.push_back(check);
  return out;
}

std::vector<CriterionResult> exact_criteria(const ExactStability& e, const Params& params) {
  std::vector<CriterionResult> out;
  const std::string integ = to_string(e.integrator);
  if (!e.computed()) return unfactored_criteria(e, params);
  CriterionResult lm =
      criterion("exact lambda_max of M^-1 K",
                "exact, safe bound (tangent stiffness; Gershgorin, shift-and-invert, Cholesky)",
                "largest eigenvalue of M^-1/2 K M^-1/2 at the state; lambda_min " +
                    (bracketed(e.spectrum.lambda_min, e.lambda_min_hi)
                         ? "certified in " + span(e.spectrum.lambda_min, e.lambda_min_hi)
                         : "= " + format_human(e.spectrum.lambda_min)));
  lm.unit = "1/s^2";
  lm.value = e.spectrum.lambda_max;
  lm.verdict = CriterionVerdict::not_applicable;
  char interval[80];  // 12 digits: the interval is ~1e-10 wide
  c_snprintf(interval, sizeof interval, "[%.12g, %.12g]", e.lambda_max_lo, e.spectrum.lambda_max);
  lm.test = "a quantity, not a test; certified in " + std::string(interval) + "; dt^2 lambda_max = " +
            format_human(params.dt * params.dt * e.spectrum.lambda_max);
  out.push_back(lm);

  CriterionResult rho = criterion("exact spectral radius (" + integ + ")", "exact",
                      std::string("rho of one step's amplification matrix; ") + to_string(e.method));
  rho.value = e.spectral_radius;
  rho.verdict = verdict_of(e.stable);
  if (e.method == ExactMethod::damped_radius && !e.radius_converged)
    rho.verdict = CriterionVerdict::not_applicable;  // an estimate from below decides nothing
  if (e.method == ExactMethod::symmetric_index || (e.spec10 && std::isnan(e.spectral_radius) &&
                                                    !std::isnan(e.index)))
    rho.test = "index lambda_max(dt^2 A + 2 dt C) = " + format_human(e.index) + (e.index < 4 ? " < 4" : " >= 4") +
               (std::isnan(e.spectral_radius) ? "" : ", rho = " + format_human(e.spectral_radius));
  else if (std::isnan(e.spectral_radius))
    rho.test = e.stable ? "stable for every dt and gamma" : "unstable";
  else
    rho.test = "rho = " + format_human(e.spectral_radius) + (e.stable ? " <= 1" : " > 1") +
               (e.radius_converged ? ""
                : e.indefinite && e.method == ExactMethod::per_mode
                    ? " (estimate: modes sampled over [lambda_min, lambda_max])"
                    : " (estimate: Arnoldi did not converge)") +
               (e.stable && e.spectral_radius >= 1 - 1e-12 ? " (marginal: no decay)" : "") +
               (e.zero_modes ? " (zero modes, lambda = 0, excluded: z = 1 for any gamma, dt)" : "");
  if (e.indefinite && !integrator_traits(e.integrator).implicit)
    rho.test += "; K is indefinite at the state (lambda_min < 0): unstable whatever gamma and dt";
  const ExactStability::Inner& in = e.inner;
  const char* only_bracketed = " (an end of the spectrum is only bracketed: ";
  if (bracketed(e.spectral_radius, in.spectral_radius)) {
    rho.verdict = bracketed_verdict(e.stable, in.stable);
    rho.test += std::string(only_bracketed) + "rho in " +
                span(in.spectral_radius, e.spectral_radius) +
                (rho.verdict == CriterionVerdict::not_applicable ? ", undecided)" : ")");
  }
  out.push_back(rho);

  CriterionResult gi = criterion("exact gamma interval (" + integ + ")", "exact",
                     "the user's gamma for which the step is stable at this dt");
  gi.unit = "mass unit/s";
  gi.value = e.gamma_hi;
  const bool inside = params.gamma >= e.gamma_lo && params.gamma < e.gamma_hi;
  gi.verdict = verdict_of(inside);
  gi.test = "gamma = " + format_human(params.gamma) + (inside ? " in " : " not in ") + "[" +
            format_human(e.gamma_lo) + ", " + format_human(e.gamma_hi) + ")" +
            (e.gamma_lo < e.gamma_hi ? "" : ": empty, no gamma is stable at this dt") +
            (e.method == ExactMethod::frozen_estimate ? " (frozen-rate estimate)" : "");

  CriterionResult dm = criterion("exact dt limit (" + integ + ")", "exact",
                     "the largest stable dt at this gamma");
  dm.unit = "s";
  dm.value = e.dt_max;
  dm.verdict = verdict_of(params.dt <= e.dt_max);
  dm.test = "dt = " + format_human(params.dt) + (params.dt <= e.dt_max ? " <= " : " > ") + "dt_max = " +
            format_human(e.dt_max) + (e.method == ExactMethod::frozen_estimate ? " (frozen-rate estimate)" : "");
  if (!e.indefinite && bracketed(e.gamma_hi, in.gamma_hi)) {
    const bool inner_inside = params.gamma >= in.gamma_lo && params.gamma < in.gamma_hi;
    gi.verdict = bracketed_verdict(inside, inner_inside);
    gi.test += std::string(only_bracketed) +
               "the stable interval holds this one and lies within [" +
               format_human(in.gamma_lo) + ", " + format_human(in.gamma_hi) + ")" +
               (gi.verdict == CriterionVerdict::not_applicable ? ", undecided)" : ")");
  }
  if (!e.indefinite && bracketed(e.dt_max, in.dt_max)) {
    dm.verdict = bracketed_verdict(params.dt <= e.dt_max, params.dt <= in.dt_max);
    dm.test += std::string(only_bracketed) + "dt_max in " + span(e.dt_max, in.dt_max) +
               (dm.verdict == CriterionVerdict::not_applicable ? ", undecided)" : ")");
  }
  if (e.method == ExactMethod::damped_radius) {
    gi.verdict = dm.verdict = CriterionVerdict::not_applicable;
    gi.test = dm.test = "not computed for this damping (dashpot or Rayleigh under " + integ +
                        "): the spectral radius above decides";
  }
  if (e.indefinite) {  // ExactStability::indefinite
    const std::string why = "K is indefinite at the state (lambda_min = " +
                            format_human(e.spectrum.lambda_min) + " < 0)";
    if (integrator_traits(e.integrator).implicit) {
      gi.verdict = dm.verdict = CriterionVerdict::not_applicable;
      gi.test = dm.test = "not computed: " + why +
                          "; implicit Euler damps its growing modes only at a long enough step, "
                          "and the spectral radius decides";
    } else {
      gi.test = "gamma = " + format_human(params.gamma) + " not in the empty interval: " +
                why + ", and a mode grows whatever gamma and dt";
      dm.test = "dt = " + format_human(params.dt) + ": no dt > 0 is stable; " + why;
    }
  }
  out.push_back(gi);
  out.push_back(dm);
  return out;
}

std::vector<CriterionResult> all_criteria(const Model& model, const State& state,
                                          const Params& params, const ExactStability& exact) {
  std::vector<CriterionResult> out = paper_criteria(model, state, params);
  for (auto& c : classic_criteria(model, params)) out.push_back(c);
  for (auto& c : exact_criteria(exact, params)) out.push_back(c);
  for (auto& c : safe_criteria(model, state, params, &exact)) out.push_back(c);
  return out;
}

Model two_node_system(const Params& params) {
  ModelSpec m;
  add_node(m, Vec3::Zero());
  add_node(m, Vec3(1, 0, 0));
  m.fixed[0] = 1;
  add_spring(m, 0, 1);
  return compile_model(std::move(m), params);
}

Model single_node_system(const Params& params) {
  ModelSpec m;
  add_node(m, Vec3::Zero());
  m.anchor_scale[0] = 1;
  return compile_model(std::move(m), params);
}

}  // namespace dampbound
