#include "core/analysis/criteria_safe.hpp"
#include "core/analysis/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
#include "core/analysis/criteria.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "core/bounds.hpp"
#include "core/forces.hpp"
#include "core/io/format.hpp"

namespace dampbound {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

CriterionResult criterion(std::string name, std::string source, std::string formula) {
  CriterionResult c;
  c.name = std::move(name);
  c.source = std::move(source);
  c.formula = std::move(formula);
  return c;
}

CriterionVerdict verdict_of(bool ok) { return ok ? CriterionVerdict::within : CriterionVerdict::beyond; }

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
  for (size_t k = 0; k < model.springs.size(); ++k) {
    const Spring& s = model.springs[k];
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
  for (size_t i = 0; i < model.rest.size(); ++i)
    if (!model.fixed[i]) {
      m_total += model.mass[i];
      ++n;
      kappa_max = std::max(kappa_max, model.node_kappa[i]);
    }
  {
    CriterionResult c = criterion("Delingette critical stiffness", "Delingette 2000 (paper ref. [11]), SPEC 7",
                      "k_c = m_total / (n pi^2 dt^2); require kappa < k_c (kappa: the stiffest "
                      "spring or anchor)");
    c.unit = "mass unit/s^2";
    c.value = n ? delingette_critical_stiffness(m_total, n, dt) : kInf;
    c.verdict = verdict_of(kappa_max < c.value);
    c.test = "kappa_max = " + format_digits(kappa_max, 8) + (kappa_max < c.value ? " < " : " >= ") +
             "k_c = " + format_digits(c.value, 8) + " (n = " + std::to_string(n) + " free nodes)";
    out.push_back(c);
  }
  const std::vector<double> K = combined_stiffness(model);
  CriterionResult provot = criterion("Provot natural period", "Provot 1995 (paper ref. [2]), SPEC 7",
                         "T0_i = pi sqrt(m_i / kappa_i), kappa_i = max incident stiffness "
                         "(SPEC 3); require dt < T0 at every node");
  provot.unit = "s";
  provot.value = kInf;
  CriterionResult ka = criterion("Kacic-Alesic (Verlet) step", "Kacic-Alesic et al. 2003 (paper ref. [12]), SPEC 7",
                     "dt_i = 2 sqrt(m_i / K_i), K_i = sum of the stiffness of every spring and "
                     "anchor at i; require dt <= dt_i at every node");
  ka.unit = "s";
  ka.value = kInf;
  for (size_t i = 0; i < model.rest.size(); ++i) {
    if (model.fixed[i]) continue;
    const double t0 = model.node_kappa[i] > 0 ? provot_natural_period(model.mass[i], model.node_kappa[i]) : kInf;
    if (t0 < provot.value) provot.value = t0, provot.node = static_cast<int>(i);
    const double tk = K[i] > 0 ? kacic_alesic_dt(model.mass[i], K[i]) : kInf;
    if (tk < ka.value) ka.value = tk, ka.node = static_cast<int>(i);
  }
  provot.verdict = verdict_of(dt < provot.value);
  provot.test = "dt = " + format_digits(dt, 8) + (dt < provot.value ? " < " : " >= ") + "T0 = " +
                format_digits(provot.value, 8) + " (worst node " + std::to_string(provot.node) + ")";
  ka.verdict = verdict_of(dt <= ka.value);
  ka.test = "dt = " + format_digits(dt, 8) + (dt <= ka.value ? " <= " : " > ") + "2 sqrt(m/K) = " +
            format_digits(ka.value, 8) + " (worst node " + std::to_string(ka.node) + ")";
  out.push_back(provot);
  out.push_back(ka);
  return out;
}

std::vector<CriterionResult> paper_criteria(const Model& model, const State& state,
                                            const Params& params) {
  std::vector<CriterionResult> out;
  CriterionResult lo = criterion("paper lower bound", "Bhasin & Liu eq. 5, SPEC 3",
                     "gamma_i >= gamma_lo_i = 2 sqrt(m_i kappa_i), kappa_i = max incident stiffness");
  lo.unit = "mass unit/s";
  double worst = kInf;
  for (size_t i = 0; i < model.rest.size(); ++i) {
    if (model.fixed[i]) continue;
    const double margin = model.gamma[i] - model.lower_bound[i];
    if (margin < worst) worst = margin, lo.node = static_cast<int>(i);
  }
  if (lo.node >= 0) {
    const auto w = static_cast<size_t>(lo.node);
    lo.value = model.lower_bound[w];
    lo.verdict = verdict_of(model.gamma[w] >= lo.value);
    lo.test = "gamma_i = " + format_digits(model.gamma[w], 8) + (model.gamma[w] >= lo.value ? " >= " : " < ") +
              "gamma_lo = " + format_digits(lo.value, 8) + " (worst node " + std::to_string(lo.node) + ")";
  }
  out.push_back(lo);

  std::vector<Vec3> force;
  internal_forces(model, state.x, force);
  CriterionResult hi = criterion("paper upper bound", "Bhasin & Liu eq. 6, SPEC 3",
                     "gamma_i <= gamma_hi_i = |v_i m_i/dt + F_i| / |v_i| at the state (inf at v_i = 0)");
  hi.unit = "mass unit/s";
  hi.value = kInf;
  CriterionResult check = criterion("paper runtime check", "Bhasin & Liu sec. 5, SPEC 3",
                        "node i unstabilisable when gamma_lo_i > gamma_hi_i");
  check.unit = "nodes";
  int unstabilisable = 0, moving = 0;
  worst = kInf;
  for (size_t i = 0; i < model.rest.size(); ++i) {
    if (model.fixed[i]) continue;
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
    hi.test = "gamma_i = " + format_digits(g, 8) + (g <= hi.value ? " <= " : " > ") + "gamma_hi = " +
              format_digits(hi.value, 8) + " (worst node " + std::to_string(hi.node) + ")";
    // Eq. 6 comes from the Euler velocity update v' = v + a dt, which the paper's step and
    // forward Euler share; for the other integrators it is shown for reference only.
    if (params.integrator != Integrator::semi_implicit_euler &&
        params.integrator != Integrator::forward_euler)
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

std::string over_budget_test(const ExactStability& exact) {
  return "not computed: " + exact.over_budget_reason();
}

namespace {

/// The exact rows over the factorisation budget: nothing exact, but what plain Lanczos and
/// Gershgorin prove without a factorisation (ExactStability::Unfactored): a bracket of
/// lambda_max, and for the paper's step a proof of instability where its Rayleigh quotient
/// reaches the index's 4. Where it does not, the row has no verdict (the safe bound's rows
/// prove stability where they can).
std::vector<CriterionResult> unfactored_criteria(const ExactStability& e, const Params& params) {
  const ExactStability::Unfactored& b = e.unfactored;
  const std::string integ = to_string(e.integrator);
  const std::string why = over_budget_test(e);
  const bool tried = !std::isnan(b.lambda_max_lo);
  const std::string without = "; without a factorisation (Lanczos, " +
                              std::to_string(b.lanczos_steps) + " steps): ";
  std::vector<CriterionResult> out;
  auto row = [&](const std::string& name) {
    CriterionResult c = criterion(name, "SPEC 7", "not computed");
    c.value = std::numeric_limits<double>::quiet_NaN();
    c.verdict = CriterionVerdict::not_applicable;
    c.test = why;
    return c;
  };
  CriterionResult lm = row("exact lambda_max of M^-1 K");
  if (tried)
    lm.test += without + "lambda_max in [" + format_digits(b.lambda_max_lo, 8) + ", " +
               format_digits(b.lambda_max_hi, 8) + "] (a Rayleigh quotient, Gershgorin's bound)";
  out.push_back(lm);
  if (b.unconditional) {  // implicit Euler, K >= 0: every row but lambda_max is exact
    auto within = [&](const std::string& name, double value, const std::string& unit,
                      const std::string& test) {
      CriterionResult c = row(name);
      c.value = value;
      c.unit = unit;
      c.verdict = CriterionVerdict::within;
      c.test += test;
      return c;
    };
    const double inf = std::numeric_limits<double>::infinity();
    out.push_back(within("exact spectral radius (" + integ + ")",
                         std::numeric_limits<double>::quiet_NaN(), "",
                         "; stable for every dt and gamma: K is positive semidefinite (SPEC 9's "
                         "floor, no spring compressed), which needs no factorisation"));
    out.push_back(within("exact gamma interval (" + integ + ")", inf, "mass unit/s",
                         "; gamma = " + format_digits(params.gamma, 8) + " in [0, inf)"));
    out.push_back(within("exact dt limit (" + integ + ")", inf, "s",
                         "; dt = " + format_digits(params.dt, 8) + " <= dt_max = inf"));
    return out;
  }
  const bool index = tried && !std::isnan(b.index_at_least);
  const bool modes = tried && !std::isnan(b.mode_unstable_from);  // forward Euler, Verlet
  CriterionResult rho = row("exact spectral radius (" + integ + ")");
  if (index) {
    const bool unstable = b.index_at_least >= 4;
    rho.verdict = unstable ? CriterionVerdict::beyond : CriterionVerdict::not_applicable;
    rho.test += without + "index lambda_max(dt^2 A + 2 dt C) >= " +
                format_digits(b.index_at_least, 8) +
                (unstable ? " >= 4: unstable (proved)" : " (< 4 proves nothing)");
  } else if (modes) {
    const bool unstable = b.lambda_max_lo >= b.mode_unstable_from;
    const bool stable_side = !std::isnan(b.stable_lambda_hi), stable = stable_side && e.stable;
    rho.verdict = unstable ? CriterionVerdict::beyond
                           : stable ? CriterionVerdict::within : CriterionVerdict::not_applicable;
    rho.test += without + "every mode with lambda >= " + format_digits(b.mode_unstable_from, 8) +
                " is unstable at this gamma and dt; lambda_max >= " +
                format_digits(b.lambda_max_lo, 8) +
                (unstable ? ": unstable (proved)" : " proves nothing");
    if (!unstable && stable_side)
      rho.test += "; every mode lies in [0, " + format_digits(b.stable_lambda_hi, 8) +
                  "] (no spring compressed: K >= 0; Gershgorin's bound)" +
                  (stable ? " and each is stable at this gamma and dt: stable (proved)"
                          : ", which proves no stability at this gamma and dt");
  }
  out.push_back(rho);
  // The user's `what` against the value from which (or up to which, `below`) the vector
  // proves instability (at the other parameter, `at`), and against the range
  // [stable_lo, stable_hi] proved stable (forward Euler and Verlet; none when NaN).
  auto threshold = [&](const std::string& name, const std::string& what, double user,
                       double from, const std::string& at, bool below,
                       double stable_lo = kNaN, double stable_hi = kNaN) {
    CriterionResult c = row(name);
    if (!index && !modes) return c;
    const bool has_stable = stable_lo <= stable_hi;  // false for NaN
    bool unstable = false, told = true;  // told: the proof names a threshold
    std::string proof;
    if (below && from == kInf) {  // gamma changes nothing (no damping rate anywhere)
      unstable = true;
      told = false;
      proof = "every " + what + " is unstable at this " + at;
    } else if (std::isinf(from)) {  // the vector proves nothing in this direction
      told = false;
      proof = "no " + what + " is proved unstable at this " + at;
    } else {
      unstable = below ? user <= from : user >= from;
      proof = "every " + what + (below ? " <= " : " >= ") + format_digits(from, 8) +
              " is unstable at this " + at;
    }
    const bool stable = !unstable && has_stable && stable_lo <= user && user <= stable_hi;
    if (has_stable) {
      const std::string range =
          stable_lo <= 0 ? (std::isinf(stable_hi) ? ">= 0" : "<= " + format_digits(stable_hi, 8))
          : std::isinf(stable_hi)
              ? ">= " + format_digits(stable_lo, 8)
              : "in [" + format_digits(stable_lo, 8) + ", " + format_digits(stable_hi, 8) + "]";
      proof += ", every " + what + " " + range + " is stable";
    }
    c.verdict = unstable ? CriterionVerdict::beyond
                         : stable ? CriterionVerdict::within : CriterionVerdict::not_applicable;
    c.test += without + proof;
    if (told || has_stable)
      c.test += "; " + what + " = " + format_digits(user, 8) +
                (unstable ? " is" : stable ? " is stable" : " is not proved either way");
    return c;
  };
  // RK4: its certificate is for the user's gamma and dt; no threshold in either.
  auto at_point = [&](const std::string& name) {
    CriterionResult c = row(name);
    c.verdict = rho.verdict;
    c.test += without + (rho.verdict == CriterionVerdict::beyond
                             ? "unstable at this gamma and dt (proved: the spectral radius row)"
                             : "not proved either way at this gamma and dt");
    return c;
  };
  const std::string gamma_row = "exact gamma interval (" + integ + ")",
                    dt_row = "exact dt limit (" + integ + ")";
  if (modes && std::isnan(b.dt_unstable_from)) {
    out.push_back(at_point(gamma_row));
    out.push_back(at_point(dt_row));
    return out;
  }
  out.push_back(modes ? threshold(gamma_row, "gamma", params.gamma, b.gamma_unstable_below, "dt",
                                  true, b.gamma_stable_lo, b.gamma_stable_hi)
                      : threshold(gamma_row, "gamma", params.gamma, b.gamma_unstable_from, "dt",
                                  false));
  out.push_back(threshold(dt_row, "dt", params.dt, b.dt_unstable_from, "gamma", false,
                          std::isnan(b.dt_stable_up_to) ? kNaN : 0.0, b.dt_stable_up_to));
  return out;
}

}  // namespace

std::vector<CriterionResult> exact_criteria(const ExactStability& e, const Params& params) {
  std::vector<CriterionResult> out;
  const std::string integ = to_string(e.integrator);
  if (!e.computed()) return unfactored_criteria(e, params);
  CriterionResult lm = criterion("exact lambda_max of M^-1 K",
                     "SPEC 7, 9 (tangent stiffness; Gershgorin, shift-and-invert, Cholesky)",
                     "largest eigenvalue of M^-1/2 K M^-1/2 at the state; lambda_min = " +
                         format_digits(e.spectrum.lambda_min, 8));
  lm.unit = "1/s^2";
  lm.value = e.spectrum.lambda_max;
  lm.verdict = CriterionVerdict::not_applicable;
  char interval[80];  // 12 digits: the interval is ~1e-10 wide
  c_snprintf(interval, sizeof interval, "[%.12g, %.12g]", e.lambda_max_lo, e.spectrum.lambda_max);
  lm.test = "a quantity, not a test; certified in " + std::string(interval) + "; dt^2 lambda_max = " +
            format_digits(params.dt * params.dt * e.spectrum.lambda_max, 8);
  out.push_back(lm);

  CriterionResult rho = criterion("exact spectral radius (" + integ + ")", "SPEC 7",
                      std::string("rho of one step's amplification matrix; ") + to_string(e.method));
  rho.value = e.spectral_radius;
  rho.verdict = verdict_of(e.stable);
  if (e.method == ExactMethod::symmetric_index)
    rho.test = "index lambda_max(dt^2 A + 2 dt C) = " + format_digits(e.index, 8) + (e.index < 4 ? " < 4" : " >= 4") +
               (std::isnan(e.spectral_radius) ? "" : ", rho = " + format_digits(e.spectral_radius, 8));
  else if (std::isnan(e.spectral_radius))
    rho.test = e.stable ? "stable for every dt and gamma" : "unstable";
  else
    rho.test = "rho = " + format_digits(e.spectral_radius, 8) + (e.stable ? " <= 1" : " > 1") +
               (e.radius_converged ? "" : " (estimate: Arnoldi did not converge)") +
               (e.stable && e.spectral_radius >= 1 - 1e-12 ? " (marginal: no decay)" : "") +
               (e.zero_modes ? " (zero modes, lambda = 0, excluded: z = 1 for any gamma, dt)" : "");
  out.push_back(rho);

  CriterionResult gi = criterion("exact gamma interval (" + integ + ")", "SPEC 7",
                     "the user's gamma for which the step is stable at this dt");
  gi.unit = "mass unit/s";
  gi.value = e.gamma_hi;
  const bool inside = params.gamma >= e.gamma_lo && params.gamma < e.gamma_hi;
  gi.verdict = verdict_of(inside);
  gi.test = "gamma = " + format_digits(params.gamma, 8) + (inside ? " in " : " not in ") + "[" +
            format_digits(e.gamma_lo, 8) + ", " + format_digits(e.gamma_hi, 8) + ")" +
            (e.method == ExactMethod::frozen_estimate ? " (frozen-rate estimate)" : "");
  out.push_back(gi);

  CriterionResult dm = criterion("exact dt limit (" + integ + ")", "SPEC 7",
                     "the largest stable dt at this gamma");
  dm.unit = "s";
  dm.value = e.dt_max;
  dm.verdict = verdict_of(params.dt <= e.dt_max);
  dm.test = "dt = " + format_digits(params.dt, 8) + (params.dt <= e.dt_max ? " <= " : " > ") + "dt_max = " +
            format_digits(e.dt_max, 8) + (e.method == ExactMethod::frozen_estimate ? " (frozen-rate estimate)" : "");
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
