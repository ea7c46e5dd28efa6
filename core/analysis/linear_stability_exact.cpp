// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/linear_stability_exact.hpp"

#include "core/analysis/damping_limits.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>

#include "core/analysis/detail/beside.hpp"
#include "core/analysis/detail/exact_over_budget.hpp"
#include "core/analysis/detail/index_limits.hpp"
#include "core/analysis/detail/shifted_cholesky.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/shared_analysis.hpp"
#include "core/physics/detail/numbers.hpp"
#include "core/physics/integrate.hpp"

namespace dampbound {
using detail::ExactInputs;
using detail::over_budget;
using detail::uniform_rates;
namespace {


/// Per free dof, gamma_scale_i / m_i: the damping rate c_i per unit of the user's gamma.
Eigen::VectorXd unit_rates(const Model& model) {
  std::vector<double> scale(model.spec().rest.size());
  for (size_t i = 0; i < scale.size(); ++i) scale[i] = model.spec().gamma_scale[i];
  return damping_rates(model, scale);
}

}  // namespace

const char* to_string(ExactMethod m) {
  switch (m) {
    case ExactMethod::per_mode: return "per-mode (uniform gamma/m)";
    case ExactMethod::symmetric_index: return "symmetric index lambda_max(dt^2 A + 2 dt C) < 4";
    case ExactMethod::unconditional: return "unconditional (A-stable)";
    case ExactMethod::frozen_estimate: return "Arnoldi rho; limits are frozen-rate estimates";
    case ExactMethod::damped_radius:
      return "rho with the dashpot and Rayleigh damping; limits not computed for this damping";
    case ExactMethod::over_budget: return "not computed (factorisation over budget)";
  }
  return "?";
}

namespace {

/// spectral_radius_at with the unit rates R (per free dof) given.
SpectralRadius radius_at(const Eigen::VectorXd& R, const SparseMatrix& K_weighted,
                         const ExactStability& e, const Params& params, double gamma) {
  if (e.uniform_rate) {
    const double r = R.size() ? R.maxCoeff() : 0;
    return {spectrum_spectral_radius(e.integrator, e.decaying, gamma * r, params.dt), true};
  }
  return amplification_spectral_radius(e.integrator, K_weighted, gamma * R, params.dt);
}

}  // namespace

SpectralRadius spectral_radius_at(const Model& model, const SparseMatrix& K_weighted,
                                  const ExactStability& e, const Params& params, double gamma) {
  return radius_at(unit_rates(model), K_weighted, e, params, gamma);
}

namespace {

ExactInputs assemble(const Model& model, const std::vector<Vec3>& x, int threads) {
  ExactInputs in;
  in.A = mass_weighted(model, tangent_stiffness(model, x, false, threads), threads);
  in.R = unit_rates(model);
  in.r_min = in.R.size() ? in.R.minCoeff() : 0;
  in.r_max = in.R.size() ? in.R.maxCoeff() : 0;
  return in;
}

void spectrum_and_rates(const ExactInputs& in, std::optional<double> floor, const Params& params,
                        const ExactOptions& options, ExactStability& e,
                        const std::function<void()>& within_budget,
                        std::unique_ptr<detail::ShiftedCholesky>& factors) {
  e.integrator = params.integrator;
  // The spectrum as certified for this A before (ExactOptions::shared), else certified here.
  CertifiedSpectrum ends;
  if (options.shared && options.shared->take(in.A, floor, options.max_factor_flops, ends, factors)) {
    if (within_budget) within_budget();
  } else {
    ends = certified_spectrum(in.A, factors, floor, options.threads, options.max_factor_flops,
                              within_budget);
    if (options.shared) options.shared->remember(in.A, floor, options.max_factor_flops, ends);
  }
  // The limit searches factor matrices of A's pattern with CHOLMOD's own ordering: where the
  // spectrum's factors have it, they go on with its pattern analysis (and the same bits as an
  // analysis of their own); otherwise (AMD alone, a small matrix) they make their own.
  if (factors && !factors->cholmod_ordering()) factors.reset();
  e.spectrum = {ends.smallest.lo, ends.largest.hi};
  // A proved floor (SPEC 9's, psd_floor) is as certain as the factorisation's end and often
  // sharper: a zero mode's end at -1e-15 would make every undamped explicit step "grow" at
  // rate sqrt(1e-15) and cut its dt limit to nothing.
  if (floor) e.spectrum.lambda_min = std::max(e.spectrum.lambda_min, *floor);
  e.lambda_max_lo = ends.largest.lo;
  e.lambda_min_hi = ends.smallest.hi;
  e.rate_min = params.gamma * in.r_min;
  e.rate_max = params.gamma * in.r_max;
  e.uniform_rate = uniform_rates(in);
  e.decaying = e.spectrum;
  const double zero = kZeroModeTolerance * std::abs(e.spectrum.lambda_max);
  if (std::abs(e.spectrum.lambda_min) <= zero) {
    e.zero_modes = true;
    const double above = smallest_eigenvalue_above(in.A, kZeroModeTolerance * e.spectrum.lambda_max);
    e.decaying.lambda_min = std::isnan(above) ? e.spectrum.lambda_max : above;
  }
  e.indefinite = ends.smallest.hi < -zero;  // a Rayleigh quotient below 0: proved
}

/// K indefinite (ExactStability::indefinite): a mode with lambda < 0 has the characteristic
/// polynomial of every explicit step below 0 at z = 1 (semi-implicit: lambda h^2), so a real
/// root beyond 1 whatever gamma and dt: no gamma is stable, and no dt. Implicit Euler damps
/// it where h mu > 2 (mu > 0 the mode's growth rate), which needs the eigenvalue nearest 0
/// from below: its limits are not computed (NaN), and where its radius came from sampling
/// [lambda_min, lambda_max] per mode, that radius is an estimate.
void indefinite_limits(ExactStability& e) {
  if (integrator_traits(e.integrator).implicit) {
    e.gamma_lo = e.gamma_hi = e.dt_max = kNaN;
    if (e.method == ExactMethod::per_mode) e.radius_converged = false;
    return;
  }
  e.gamma_lo = e.gamma_hi = 0;
  e.dt_max = 0;
  e.stable = false;
  // Proved (a Rayleigh quotient below 0), so the inner ends' numbers are these too.
  e.inner.gamma_lo = e.inner.gamma_hi = e.inner.dt_max = 0;
  e.inner.stable = false;
}

/// The spectral radius of the step's amplification operator, when asked for (else NaN).
void add_radius(const ExactInputs& in, const Params& params, const ExactOptions& options,
                ExactStability& e) {
  e.spectral_radius = kNaN;
  if (!options.with_radius) return;
  const SpectralRadius s = radius_at(in.R, in.A, e, params, params.gamma);
  e.spectral_radius = s.rho;
  e.radius_converged = s.converged;
}

/// The spectral radius at non-uniform rates (Spectra's Arnoldi on the amplification operator:
/// Eigen's and dampbound's own code, neither CHOLMOD nor a BLAS) needs nothing the certified
/// eigenvalues give, and these spend most of their time in factorisations on one core. On two
/// or more threads, where the radius is asked for, start() runs it on a thread of its own
/// beside them; its bits are those of one thread, on a copy of what it reads. add_to() takes
/// its result, or computes it there when it was not started. Should the caller throw once it
/// has started (nothing does after the budget is cleared), the destructor joins it first.
class RadiusBeside {
 public:
  RadiusBeside(const ExactInputs& in, const Params& params, const ExactOptions& options)
      : in_(in), params_(params), options_(options) {}
  void start() {
    if (thread_ || !options_.with_radius || uniform_rates(in_) ||
        detail::resolved_threads(options_.threads) < 2)
      return;
    thread_ = std::make_unique<detail::Beside>([this] {
      ExactStability r;
      r.integrator = params_.integrator;
      r.uniform_rate = false;
      add_radius(in_, params_, options_, r);
      radius_ = {r.spectral_radius, r.radius_converged};
    });
  }
  void add_to(ExactStability& e) {
    if (!thread_) return add_radius(in_, params_, options_, e);
    thread_->finish();
    e.spectral_radius = radius_.rho;
    e.radius_converged = radius_.converged;
  }

 private:
  const ExactInputs& in_;
  const Params& params_;
  const ExactOptions& options_;
  SpectralRadius radius_;
  std::unique_ptr<detail::Beside> thread_;  // last: joined before the members above go
};

/// Backward Euler on M y'' = -K y - Gamma y' with K, Gamma >= 0 dissipates the energy
/// y'^T M y' + y^T K y every step, for every h: no limit on dt or gamma.
void unconditional(ExactStability& e) {
  e.method = ExactMethod::unconditional;
  e.gamma_lo = 0;
  e.gamma_hi = kInf;
  e.dt_max = kInf;
  e.stable = true;
}

/// Uniform rates c = gamma r_max: every mode is a scalar recurrence, and the numbers are exact
/// per mode over `spectrum` (`decaying`: without its zero modes).
ExactStability::Inner per_mode_over(Integrator integrator, const StiffnessSpectrum& spectrum,
                                    const StiffnessSpectrum& decaying, double r_max,
                                    const Params& params) {
  const double h = params.dt;
  const double c = params.gamma * r_max;
  ExactStability::Inner n;
  n.spectral_radius = spectrum_spectral_radius(integrator, decaying, c, h);
  n.stable = spectrum_spectral_radius(integrator, spectrum, c, h) <= 1 + 1e-12;
  // The paper's step: SPEC 7's predicate as well (lambda_max h^2 + 2 c h < 4, c h < 2), as the
  // symmetric index decides at non-uniform rates and as the printed gamma_hi and dt_max say.
  // The radius alone counts |z| = 1 + 1e-12 as bounded: "stable" up to 1e-12 past the limits,
  // where over the budget the same vector's index proves the step unstable.
  if (integrator_traits(integrator).paper_step)
    n.stable = n.stable && spectrum.lambda_max * h * h + 2 * c * h < 4 && c * h < 2;
  const RateInterval ci = uniform_rate_interval(integrator, spectrum, h);
  if (r_max > 0) {
    n.gamma_lo = ci.lo / r_max;
    n.gamma_hi = ci.hi / r_max;
  } else {  // no node is damped: gamma has no effect
    n.gamma_lo = 0;
    n.gamma_hi = ci.lo == 0 && !ci.empty() ? kInf : 0;
  }
  n.dt_max = uniform_dt_max(integrator, spectrum, c);
  return n;
}

/// The numbers over the certified outer ends, and over the inner ones (ExactStability::Inner).
void per_mode(const ExactInputs& in, const Params& params, ExactStability& e) {
  e.method = ExactMethod::per_mode;
  const ExactStability::Inner outer =
      per_mode_over(e.integrator, e.spectrum, e.decaying, in.r_max, params);
  e.spectral_radius = outer.spectral_radius;
  e.stable = outer.stable;
  e.gamma_lo = outer.gamma_lo;
  e.gamma_hi = outer.gamma_hi;
  e.dt_max = outer.dt_max;
  // A single eigenvalue (lambda_min = lambda_max) has inner ends that may cross: keep them in
  // order, each still within its own end's interval.
  const double top = e.lambda_max_lo;
  const StiffnessSpectrum inner{std::min(e.lambda_min_hi, top), top};
  const StiffnessSpectrum inner_decaying{
      e.zero_modes ? std::min(e.decaying.lambda_min, top) : inner.lambda_min, top};
  e.inner = per_mode_over(e.integrator, inner, inner_decaying, in.r_max, params);
}

/// Forward Euler, Verlet, RK4 (and implicit Euler at an indefinite K) with non-uniform
/// rates: the limits from the worst uniform rate over [c_min, c_max] ("frozen
/// coefficients", an estimate); the verdict from the amplification operator when measured.
void frozen_estimate(const ExactInputs& in, const Params& params, ExactStability& e) {
  e.method = ExactMethod::frozen_estimate;
  const RateInterval ci = uniform_rate_interval(e.integrator, e.spectrum, params.dt);
  e.gamma_lo = in.r_min > 0 ? ci.lo / in.r_min : (ci.lo == 0 ? 0 : kInf);
  e.gamma_hi = ci.hi / in.r_max;
  e.dt_max = kInf;
  for (int k = 0; k <= 16; ++k) {
    const double c = e.rate_min + (e.rate_max - e.rate_min) * k / 16;
    e.dt_max = std::min(e.dt_max, uniform_dt_max(e.integrator, e.spectrum, c));
  }
}

/// SPEC 10: the paper's step with dashpot or Rayleigh damping. The limits and the verdict
/// become the generalised index's (general_limits: the Rayleigh closed forms where C^ commutes
/// with A, else bisection on lambda_max(dt^2 A + 2 dt C^)); the nodal spectral radius and its
/// inner bracket no longer describe the step and are dropped (NaN).
void with_spec10_damping(const Model& model, const std::vector<Vec3>& x, const Params& params,
                         const ExactOptions& options, ExactStability& e,
                         std::unique_ptr<detail::ShiftedCholesky>& factors) {
  const GeneralLimits g =
      general_limits(model, x, params, e.spectrum, options.max_factor_flops, &factors);
  e.spec10 = true;
  e.general = g;
  e.method = g.commuting ? ExactMethod::per_mode : ExactMethod::symmetric_index;
  e.index = g.index;
  e.gamma_lo = 0;
  e.gamma_hi = std::max(g.gamma_max, 0.0);
  e.dt_max = g.dt_max;
  e.stable = g.index < 4;
  e.spectral_radius = kNaN;
  // The general limits are one number each (no certified bracket of inner ends).
  e.inner = ExactStability::Inner{};
  e.inner.gamma_lo = e.gamma_lo;
  e.inner.gamma_hi = e.gamma_hi;
  e.inner.dt_max = e.dt_max;
  e.inner.stable = e.stable;
}

/// SPEC 10's damping under the other integrators (docs/criteria.md, "The other integrators"):
/// implicit Euler stays unconditional, its radius not quoted without C'; the explicit ones get
/// no limits (NaN) and the verdict of the radius with the whole damping, if it converged.
void with_spec10_radius(const Model& model, const std::vector<Vec3>& x, const ExactInputs& in,
                        const Params& params, ExactStability& e) {
  e.spec10 = true;
  e.inner = ExactStability::Inner{};
  e.spectral_radius = kNaN;
  if (integrator_traits(e.integrator).implicit) return;
  e.method = ExactMethod::damped_radius;
  e.index = kNaN;
  e.gamma_lo = e.gamma_hi = e.dt_max = kNaN;
  const SparseMatrix Cp =
      weighted_damping(model, x, std::vector<double>(model.spec().rest.size(), 0.0));
  const Eigen::VectorXd rate = params.gamma * in.R;
  const SpectralRadius r = amplification_spectral_radius(e.integrator, in.A, rate, params.dt, &Cp);
  e.spectral_radius = r.rho;
  e.radius_converged = r.converged;
  e.stable = r.converged && r.rho <= 1 + 1e-9;
}

/// `spec10`: SPEC 10's limits replace the nodal ones where K is not indefinite
/// (with_spec10_damping), so only the spectrum is computed then: no radius, no nodal limits.
/// `factors`: the spectrum's and the limit searches' factorisations, left for the caller
/// (SPEC 10's index and searches, ExactOptions::shared).
ExactStability exact_stability_within_budget(const ExactInputs& in, std::optional<double> floor,
                                             const Params& params, const ExactOptions& options,
                                             bool spec10,
                                             std::unique_ptr<detail::ShiftedCholesky>& factors) {
  ExactStability e;
  // The radius beside the factorisations: the symmetric index's (semi-implicit Euler), else,
  // for forward Euler, Verlet and RK4, the spectrum's, once their analysis clears the budget.
  // Implicit Euler needs it only at an indefinite K, which the spectrum says.
  RadiusBeside radius(in, params, options);
  const IntegratorTraits& t = integrator_traits(params.integrator);
  const bool frozen = !t.paper_step && !t.implicit;
  spectrum_and_rates(in, floor, params, options, e,
                     frozen ? std::function<void()>([&] { radius.start(); }) : nullptr, factors);
  if (spec10 && !e.indefinite) return e;
  const double tiny = 1e-12 * std::max(1.0, std::abs(e.spectrum.lambda_max));
  if (integrator_traits(e.integrator).implicit && e.spectrum.lambda_min >= -tiny) {
    unconditional(e);
    e.spectral_radius = kNaN;
    if (e.uniform_rate) add_radius(in, params, options, e);
  } else if (e.uniform_rate) {
    per_mode(in, params, e);
  } else if (integrator_traits(e.integrator).paper_step) {
    radius.start();
    detail::symmetric_index_limits(in, params, options, e, factors);
    radius.add_to(e);
  } else {
    frozen_estimate(in, params, e);
    radius.add_to(e);
    e.stable = std::isnan(e.spectral_radius)
                   ? (params.gamma >= e.gamma_lo && params.gamma < e.gamma_hi &&
                      params.dt <= e.dt_max)
                   : e.spectral_radius <= 1 + 1e-9;
  }
  if (e.indefinite) indefinite_limits(e);
  return e;
}

}  // namespace

ExactStability exact_stability(const Model& model, const std::vector<Vec3>& x,
                               const Params& params, const ExactOptions& options) {
  const ExactInputs in = assemble(model, x, options.threads);
  try {
    const bool spec10 = model.spring_damping && integrator_traits(params.integrator).paper_step;
    std::unique_ptr<detail::ShiftedCholesky> factors;
    ExactStability e = exact_stability_within_budget(in, psd_floor(model, x), params, options,
                                                     spec10, factors);
    if (model.spring_damping && !e.indefinite) {
      if (spec10)
        with_spec10_damping(model, x, params, options, e, factors);
      else
        with_spec10_radius(model, x, in, params, e);
    }
    if (options.shared) options.shared->keep(std::move(factors));
    return e;
  } catch (const FactorisationOverBudget& over) {
    return over_budget(model, x, in, params, options, over);
  }
}

ExactStability exact_stability(const SparseMatrix& A, const Eigen::VectorXd& R,
                               std::optional<double> floor, const Params& params,
                               const ExactOptions& options) {
  ExactInputs in;
  in.A = A;
  in.R = R;
  in.r_min = R.size() ? R.minCoeff() : 0;
  in.r_max = R.size() ? R.maxCoeff() : 0;
  std::unique_ptr<detail::ShiftedCholesky> factors;
  ExactStability e = exact_stability_within_budget(in, floor, params, options, false, factors);
  if (options.shared) options.shared->keep(std::move(factors));
  return e;
}

}  // namespace dampbound
