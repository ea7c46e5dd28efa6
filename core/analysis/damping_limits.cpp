#include "core/analysis/damping_limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/stiffness.hpp"
#include "core/analysis/linear_stability.hpp"
#include "core/analysis/linear_stability_modes.hpp"

namespace dampbound {

DampingRatios damping_ratios(const Model& model, const std::vector<Vec3>& x) {
  DampingRatios r;
  constexpr double kInf = std::numeric_limits<double>::infinity();
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
  const StiffnessSpectrum sp = stiffness_spectrum(model, x);
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

namespace {

/// The largest stable x with f(x) = lambda_max(S(x)) - 4 < 0, where S(x) is positive
/// semi-definite, increasing and convex in x (so is f), bracketed by lo (stable) and hi
/// (unstable). Each round takes Newton's step from the unstable end (a convex f's tangent
/// meets 0 on the unstable side) and the chord's root (on the stable side), every point
/// placed by the sign of its certified eigenvalue, halving where neither shrinks the bracket
/// enough: to 1e-10 relative in a handful of eigensolves where bisection takes about 35.
template <class Matrix, class Slope>
double index_root(Matrix&& S, Slope&& dS, double lo, double hi) {
  struct Point {
    double x, f, slope;
  };
  const auto eval = [&](double x) {
    Eigen::VectorXd v;
    const double lambda = largest_eigenpair(S(x), v);
    const double norm = v.squaredNorm();
    return Point{x, lambda - 4, norm > 0 ? v.dot(dS(x) * v) / norm : 0.0};
  };
  Point a = eval(lo), b = eval(hi);
  const auto place = [&](double x) {
    if (!(x > a.x && x < b.x)) return;
    const Point p = eval(x);
    (p.f < 0 ? a : b) = p;
  };
  for (int k = 0; k < 100 && b.x - a.x > 1e-10 * b.x; ++k) {
    const double width = b.x - a.x;
    if (b.slope > 0) place(b.x - b.f / b.slope);
    if (b.f > a.f) place(a.x - a.f * (b.x - a.x) / (b.f - a.f));
    if (b.x - a.x > 0.5 * width) place(0.5 * (a.x + b.x));
  }
  return a.x;
}

}  // namespace

GeneralLimits general_limits(const SparseMatrix& A, const SparseMatrix& Cp, const SparseMatrix& G,
                             double gamma, double dt) {
  GeneralLimits g;
  const auto index = [&](double gm, double h) {
    const SparseMatrix S = (h * h) * A + (2 * h) * (Cp + gm * G);
    return largest_eigenvalue(S);
  };
  g.index = index(gamma, dt);
  g.damping_min = smallest_eigenvalue(Cp + gamma * G);
  g.gamma_max = largest_stable_coefficient(A, Cp, G, dt);
  // The index grows with dt (A, C^ positive semi-definite) and is convex in it.
  double hi = dt;
  for (int k = 0; k < 200 && index(gamma, hi) < 4; ++k) hi *= 2;
  double lo = hi;
  for (int k = 0; k < 200 && !(index(gamma, lo) < 4); ++k) lo /= 2;
  if (!(lo < hi)) hi = 2 * lo;
  const SparseMatrix C = Cp + gamma * G;
  g.dt_max = index_root([&](double h) -> SparseMatrix { return (h * h) * A + (2 * h) * C; },
                        [&](double h) -> SparseMatrix { return (2 * h) * A + 2.0 * C; }, lo, hi);
  return g;
}

double largest_stable_coefficient(const SparseMatrix& A, const SparseMatrix& C,
                                  const SparseMatrix& U, double dt) {
  const SparseMatrix base = (dt * dt) * A + (2 * dt) * C, step = (2 * dt) * U;
  const auto stable = [&](double v) { return largest_eigenvalue(base + v * step) < 4; };
  if (!stable(0)) return 0;
  double lo = 0, hi = 1;
  for (int k = 0; k < 200 && stable(hi); ++k) lo = hi, hi *= 2;
  if (stable(hi)) return std::numeric_limits<double>::infinity();
  return index_root([&](double v) -> SparseMatrix { return base + v * step; },
                    [&](double) -> const SparseMatrix& { return step; }, lo, hi);
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
                        DampingKind kind) {
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
  return largest_stable_coefficient(A, C, U, params.dt);
}

GeneralLimits general_limits(const Model& model, const std::vector<Vec3>& x, const Params& params) {
  const double dt = params.dt;
  const SparseMatrix A = mass_weighted(model, tangent_stiffness(model, x));
  SparseMatrix Cp = weighted_damping(model, x, std::vector<double>(model.spec().rest.size(), 0.0));
  // The nodal part per unit user gamma: gamma_scale_i / m_i on node i's rows, built as the
  // diagonal it is: weighted_damping(scales) - C' would keep only the digits of
  // gamma_scale_i / m_i above C''s last bit, and a large gamma multiplies the loss.
  std::vector<double> unit(model.spec().rest.size());
  for (size_t i = 0; i < unit.size(); ++i) unit[i] = model.spec().gamma_scale[i];
  const Eigen::VectorXd rates = damping_rates(model, unit);
  SparseMatrix G(rates.size(), rates.size());
  G.reserve(Eigen::VectorXi::Constant(rates.size(), 1));
  for (Eigen::Index r = 0; r < rates.size(); ++r) G.insert(r, r) = rates(r);
  G.makeCompressed();
  // Commuting: no dashpot, and gamma_i / m_i the same at every free node.
  bool dashpot = false;
  for (double kd : model.spring_kd) dashpot = dashpot || kd != 0;
  for (double kd : model.anchor_kd) dashpot = dashpot || kd != 0;
  double rate = -1;
  bool uniform = true;
  for (size_t i = 0; i < model.spec().rest.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const double c = model.spec().gamma_scale[i] / model.mass[i];
    if (rate < 0) rate = c;
    uniform = uniform && c == rate;
  }
  if (!(!dashpot && uniform && rate > 0)) return general_limits(A, Cp, G, params.gamma, dt);
  GeneralLimits g;
  g.commuting = true;
  g.index = largest_eigenvalue((dt * dt) * A + (2 * dt) * (Cp + params.gamma * G));
  g.damping_min = smallest_eigenvalue(Cp + params.gamma * G);
  // c(lambda) = gamma/m + alpha + beta lambda; the binding mode is lambda_max.
  const double lmax = largest_eigenvalue(A);
  const double m = 1.0 / rate;  // m_i / gamma_scale_i
  const double alpha = model.rayleigh_mass, beta = model.rayleigh_stiffness;
  g.gamma_max = 2 * m / dt - m * lmax * dt / 2 - m * alpha - m * beta * lmax;
  g.dt_max = semi_implicit_dt_max(lmax, params.gamma * rate + alpha + beta * lmax);
  return g;
}

}  // namespace dampbound
