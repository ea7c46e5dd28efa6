#include "core/analysis/damping_limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/analysis/detail/definite_root.hpp"
#include "core/analysis/detail/shifted_cholesky.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/linear_stability_modes.hpp"
#include "core/physics/detail/numbers.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/stiffness.hpp"

namespace dampbound {

DampingRatios damping_ratios(const Model& model, const std::vector<Vec3>& x) {
  return damping_ratios(model, x, stiffness_spectrum(model, x));
}

DampingRatios damping_ratios(const Model& model, const std::vector<Vec3>&,
                             const StiffnessSpectrum& sp) {
  DampingRatios r;
  r.nodal_min = r.dashpot_min = kInf;
  r.nodal_max = r.dashpot_max = 0;
  for (size_t i = 0; i < model.spec().rest.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const double z = model.lower_bound[i] > 0 ? model.gamma[i] / model.lower_bound[i] : kInf;
    r.nodal_min = std::min(r.nodal_min, z);
    r.nodal_max = std::max(r.nodal_max, z);
    if (model.anchor_kd[i] > 0) {  // an anchor's reduced mass is m_i
      const double zd = model.anchor_kd[i] / (2 * std::sqrt(model.mass[i] * model.anchor_kappa[i]));
      ++r.dashpots;
      r.dashpot_min = std::min(r.dashpot_min, zd);
      r.dashpot_max = std::max(r.dashpot_max, zd);
    }
  }
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    if (!(model.spring_kd[k] > 0)) continue;
    const Spring& s = model.spec().springs[k];
    const size_t i = static_cast<size_t>(s.i), j = static_cast<size_t>(s.j);
    if (model.spec().fixed[i] && model.spec().fixed[j]) continue;
    const double mu = model.spec().fixed[i]   ? model.mass[j]
                      : model.spec().fixed[j] ? model.mass[i]
                                       : model.mass[i] * model.mass[j] / (model.mass[i] + model.mass[j]);
    const double zd = model.spring_kd[k] / (2 * std::sqrt(mu * model.spring_kappa[k]));
    ++r.dashpots;
    r.dashpot_min = std::min(r.dashpot_min, zd);
    r.dashpot_max = std::max(r.dashpot_max, zd);
  }
  if (r.dashpots == 0) r.dashpot_min = 0;
  if (!std::isfinite(r.nodal_min)) r.nodal_min = 0;
  r.lambda_min = sp.lambda_min;
  r.lambda_max = sp.lambda_max;
  auto zeta = [&](double lambda) {
    return lambda > 0 ? (model.rayleigh_mass + model.rayleigh_stiffness * lambda) /
                            (2 * std::sqrt(lambda))
                      : (model.rayleigh_mass > 0 ? kInf : 0.0);
  };
  r.rayleigh_low = zeta(r.lambda_min);
  r.rayleigh_high = zeta(r.lambda_max);
  return r;
}

GeneralLimits general_limits(const SparseMatrix& A, const SparseMatrix& Cp, const SparseMatrix& G,
                             double gamma, double dt, double max_factor_flops,
                             std::unique_ptr<detail::ShiftedCholesky>* shared,
                             double damping_floor) {
  GeneralLimits g;
  const SparseMatrix C = Cp + gamma * G;
  // The index and both searches on the pattern of A + Cp + G: one pattern analysis where it is
  // CHOLMOD's own choice of ordering (the searches' own would be the same, to the bit), or
  // the caller's where that has the same pattern.
  std::unique_ptr<detail::ShiftedCholesky> own;
  std::unique_ptr<detail::ShiftedCholesky>& factors = shared ? *shared : own;
  Eigen::VectorXd top;  // the index's top vector: where both searches' Lanczos runs start
  g.index = certified_largest_eigenvalue((dt * dt) * A + (2 * dt) * C, factors, 1,
                                         max_factor_flops, &top).hi;
  if (factors && !factors->cholmod_ordering()) factors.reset();
  g.damping_min = damping_floor > 0
                      ? damping_floor
                      : certified_smallest_eigenvalue(C, std::nullopt, 1, max_factor_flops).lo;
  {
    const SparseMatrix base = (dt * dt) * A + (2 * dt) * Cp, step = (2 * dt) * G;
    detail::IndexFamily family;
    family.S = [&](double v) -> SparseMatrix { return base + v * step; };
    family.D = [&](double) -> SparseMatrix { return step; };
    family.start = top;
    g.gamma_max = detail::definite_root(family, 0, &factors, max_factor_flops).stable;
  }
  // The index in h: S(a + t) = S(a) + t (2 a A + 2 C) + t^2 A, from the scene's dt.
  detail::IndexFamily family;
  family.S = [&](double h) -> SparseMatrix { return (h * h) * A + (2 * h) * C; };
  family.D = [&](double h) -> SparseMatrix { return (2 * h) * A + 2.0 * C; };
  family.Q = A;
  family.start = top;
  g.dt_max = detail::definite_root(family, dt, &factors, max_factor_flops).stable;
  return g;
}

double damping_floor(const Model& model, double gamma, double a_floor, const SparseMatrix& A,
                     const SparseMatrix& C) {
  const double alpha = model.rayleigh_mass, beta = model.rayleigh_stiffness;
  bool signs = alpha >= 0 && beta >= 0 && std::isfinite(a_floor);
  for (double kd : model.spring_kd) signs = signs && kd >= 0;
  if (!signs) return kNaN;
  double d_min = kInf;
  for (size_t i = 0; i < model.spec().rest.size(); ++i)
    if (!model.spec().fixed[i])
      d_min = std::min(d_min, (gamma * model.spec().gamma_scale[i] + model.anchor_kd[i]) /
                                  model.mass[i]);
  if (!std::isfinite(d_min)) return kNaN;  // no free node
  const GershgorinBounds ga = gershgorin_bounds(A), gc = gershgorin_bounds(C);
  const double size = std::max(std::abs(gc.lo), std::abs(gc.hi)) +
                      beta * std::max(std::abs(ga.lo), std::abs(ga.hi));
  return alpha + beta * a_floor + d_min - 1e-10 * size;
}

SharedFactors::SharedFactors() = default;
SharedFactors::~SharedFactors() = default;

double largest_stable_coefficient(const SparseMatrix& A, const SparseMatrix& C,
                                  const SparseMatrix& U, double dt, double max_factor_flops,
                                  SharedFactors* shared) {
  const SparseMatrix base = (dt * dt) * A + (2 * dt) * C, step = (2 * dt) * U;
  detail::IndexFamily family;
  family.S = [&](double v) -> SparseMatrix { return base + v * step; };
  family.D = [&](double) -> SparseMatrix { return step; };
  return detail::definite_root(family, 0, shared ? &shared->factors : nullptr, max_factor_flops)
      .stable;
}

const char* to_string(DampingKind kind) {
  switch (kind) {
    case DampingKind::nodal: return "gamma";
    case DampingKind::dashpot: return "kd";
    case DampingKind::rayleigh_mass: return "rayleigh_mass";
    case DampingKind::rayleigh_stiffness: return "rayleigh_stiffness";
  }
  return "?";
}

double& coefficient(Params& params, DampingKind kind) {
  switch (kind) {
    case DampingKind::nodal: return params.gamma;
    case DampingKind::dashpot: return params.kd;
    case DampingKind::rayleigh_mass: return params.rayleigh_mass;
    case DampingKind::rayleigh_stiffness: return params.rayleigh_stiffness;
  }
  return params.gamma;
}

double damping_kind_max(const ModelSpec& spec, const std::vector<Vec3>& x, const Params& params,
                        DampingKind kind, double max_factor_flops, SharedFactors* shared) {
  // C: every damping but this kind's; U: this kind per unit coefficient (the nodal part
  // through weighted_damping's gamma_i, the others through a model with only that one on).
  Params held = params, unit = params;
  coefficient(held, kind) = 0;
  unit.gamma = unit.kd = unit.rayleigh_mass = unit.rayleigh_stiffness = 0;
  unit.zeta.reset();
  held.zeta.reset();
  coefficient(unit, kind) = 1;
  const Model with_held = compile_model(spec, held), only = compile_model(spec, unit);
  const SparseMatrix A = mass_weighted(with_held, tangent_stiffness(with_held, x));
  const SparseMatrix C = weighted_damping(with_held, x, with_held.gamma);
  const SparseMatrix U = weighted_damping(only, x, only.gamma);
  return largest_stable_coefficient(A, C, U, params.dt, max_factor_flops, shared);
}

namespace {

/// The matrices of SPEC 10 at x: A = M^-1/2 K M^-1/2, Cp the damping besides the nodal one,
/// G the nodal damping per unit user gamma (gamma_scale_i / m_i on node i's rows); and whether
/// C^ = Cp + gamma G commutes with A: no dashpot, and gamma = 0 (C^ = alpha I + beta A) or
/// gamma_i / m_i the same at every free node (`rate`, then > 0).
struct Spec10Parts {
  SparseMatrix A, Cp, G;
  bool uniform = false;
  double rate = -1;
  bool commutes = false;
};

Spec10Parts spec10_parts(const Model& model, const std::vector<Vec3>& x, const Params& params) {
  Spec10Parts s;
  s.A = mass_weighted(model, tangent_stiffness(model, x));
  s.Cp = weighted_damping(model, x, std::vector<double>(model.spec().rest.size(), 0.0));
  // G built as the diagonal it is: weighted_damping(scales) - C' would keep only the digits of
  // gamma_scale_i / m_i above C''s last bit, and a large gamma multiplies the loss.
  std::vector<double> unit(model.spec().rest.size());
  for (size_t i = 0; i < unit.size(); ++i) unit[i] = model.spec().gamma_scale[i];
  const Eigen::VectorXd rates = damping_rates(model, unit);
  s.G = SparseMatrix(rates.size(), rates.size());
  s.G.reserve(Eigen::VectorXi::Constant(rates.size(), 1));
  for (Eigen::Index r = 0; r < rates.size(); ++r) s.G.insert(r, r) = rates(r);
  s.G.makeCompressed();
  bool dashpot = false;
  for (double kd : model.spring_kd) dashpot = dashpot || kd != 0;
  for (double kd : model.anchor_kd) dashpot = dashpot || kd != 0;
  bool uniform = true;
  for (size_t i = 0; i < model.spec().rest.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const double c = model.spec().gamma_scale[i] / model.mass[i];
    if (s.rate < 0) s.rate = c;
    uniform = uniform && c == s.rate;
  }
  s.uniform = !dashpot && uniform && s.rate > 0;
  s.commutes = !dashpot && (s.uniform || params.gamma == 0);
  return s;
}

/// SPEC 10's closed forms where C^ commutes with A (general_limits' second overload).
GeneralLimits closed_forms(const Model& model, const Params& params, const Spec10Parts& s,
                           const StiffnessSpectrum& spectrum, double max_factor_flops) {
  const double dt = params.dt;
  // Every mode of A (eigenvalue lambda) has the rate c(lambda) = c0 + beta lambda (SPEC 10).
  const double alpha = model.rayleigh_mass, beta = model.rayleigh_stiffness;
  const double lmax = spectrum.lambda_max, lmin = spectrum.lambda_min;
  const double c0 = (params.gamma == 0 ? 0.0 : params.gamma * s.rate) + alpha;
  GeneralLimits g;
  g.commuting = s.uniform;
  // The certified upper end of lambda_max makes f(lambda_max) an upper end of the index,
  // rounded up past the few roundings of f.
  const double index = dt * dt * lmax + 2 * dt * (c0 + beta * lmax);
  g.index = index * (1 + 8 * std::numeric_limits<double>::epsilon());
  g.damping_min = c0 + beta * lmin;
  g.dt_max = semi_implicit_dt_max(lmax, c0 + beta * lmax);
  if (s.uniform) {
    const double m = 1.0 / s.rate;  // m_i / gamma_scale_i
    g.gamma_max = 2 * m / dt - m * lmax * dt / 2 - m * alpha - m * beta * lmax;
  } else {  // gamma = 0: gamma G does not commute with A once gamma > 0
    g.gamma_max =
        g.index < 4 ? largest_stable_coefficient(s.A, s.Cp, s.G, dt, max_factor_flops) : 0;
  }
  return g;
}

}  // namespace

GeneralLimits general_limits(const Model& model, const std::vector<Vec3>& x, const Params& params,
                             double max_factor_flops) {
  const Spec10Parts s = spec10_parts(model, x, params);
  if (!s.commutes) {
    const std::optional<double> a_floor = psd_floor(model, x);
    const double floor = a_floor ? damping_floor(model, params.gamma, *a_floor, s.A,
                                                 s.Cp + params.gamma * s.G)
                                 : kNaN;
    return general_limits(s.A, s.Cp, s.G, params.gamma, params.dt, max_factor_flops, nullptr,
                          floor);
  }
  const CertifiedSpectrum ends = certified_spectrum(s.A, psd_floor(model, x), 1, max_factor_flops);
  return closed_forms(model, params, s, {ends.smallest.lo, ends.largest.hi}, max_factor_flops);
}

GeneralLimits general_limits(const Model& model, const std::vector<Vec3>& x, const Params& params,
                             const StiffnessSpectrum& spectrum, double max_factor_flops,
                             std::unique_ptr<detail::ShiftedCholesky>* factors) {
  const Spec10Parts s = spec10_parts(model, x, params);
  if (!s.commutes) {
    const double floor = damping_floor(model, params.gamma, spectrum.lambda_min, s.A,
                                       s.Cp + params.gamma * s.G);
    return general_limits(s.A, s.Cp, s.G, params.gamma, params.dt, max_factor_flops, factors,
                          floor);
  }
  return closed_forms(model, params, s, spectrum, max_factor_flops);
}

}  // namespace dampbound
