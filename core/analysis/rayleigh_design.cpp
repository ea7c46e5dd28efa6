#include "core/analysis/rayleigh_design.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "core/analysis/damping_limits.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/suggest.hpp"
#include "core/io/format.hpp"
#include "core/physics/integrate.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/physics/stiffness.hpp"

namespace dampbound {

namespace {
constexpr double kTwoPi = 6.283185307179586;

/// C^ commutes with A: no dashpot and gamma_i / m_i the same at every free node (SPEC 10).
bool commuting(const Model& model, double& rate) {
  for (double kd : model.spring_kd)
    if (kd != 0) return false;
  for (double kd : model.anchor_kd)
    if (kd != 0) return false;
  rate = -1;
  for (size_t i = 0; i < model.mass.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const double c = model.gamma[i] / model.mass[i];
    if (rate >= 0 && c != rate) return false;
    rate = c;
  }
  return rate >= 0;
}
}  // namespace

double rayleigh_zeta(double alpha, double beta, double f) {
  const double w = kTwoPi * f;
  return alpha / (2 * w) + beta * w / 2;
}

std::pair<double, double> rayleigh_pair(double f1, double zeta1, double f2, double zeta2) {
  const double w1 = kTwoPi * f1, w2 = kTwoPi * f2, d = w2 * w2 - w1 * w1;
  return {2 * w1 * w2 * (zeta1 * w2 - zeta2 * w1) / d, 2 * (zeta2 * w2 - zeta1 * w1) / d};
}

RayleighDesign rayleigh_from_spectrum(const SceneSpec& scene, const Params& params,
                                      const RayleighRequest& request,
                                      const std::function<bool(const std::string&)>& progress,
                                      double max_factor_flops) {
  const auto stage = [&](const std::string& next) {
    if (progress && !progress(next)) throw SuggestCancelled();
  };
  if (!integrator_traits(params.integrator).paper_step)
    throw InputError(std::string("--rayleigh: the exact index is the paper's step's "
                                 "(semi-implicit-euler), not ") + to_string(params.integrator));
  if (!(request.zeta1 > 0) || !(request.zeta2 > 0) || !std::isfinite(request.zeta1) ||
      !std::isfinite(request.zeta2))
    throw InputError("--rayleigh: the damping ratios must be finite and > 0");
  Params p = params;
  p.zeta.reset();
  p.rayleigh_mass = p.rayleigh_stiffness = 0;
  const Model bare = compile_model(scene.model, p);
  const std::vector<Vec3>& x = bare.spec().rest;
  const SparseMatrix A = mass_weighted(bare, tangent_stiffness(bare, x));
  RayleighDesign d;
  if (A.rows() == 0) throw InputError("--rayleigh: the scene has no free node");
  stage("stage 1 of 3: the lowest and highest eigenvalue of M^-1 K (" +
        std::to_string(A.rows()) + " rows)");
  d.lambda_max = certified_largest_eigenvalue(A, nullptr, 1, max_factor_flops).hi;
  d.lambda_min = smallest_eigenvalue_above(A, kZeroModeTolerance * d.lambda_max);
  if (!(d.lambda_max > 0) || !(d.lambda_min > 0))
    throw InputError("--rayleigh: the model has no mode that a spring resists");
  d.f_lowest = std::sqrt(d.lambda_min) / kTwoPi;
  d.f_highest = std::sqrt(d.lambda_max) / kTwoPi;
  d.f_nyquist = 1 / (2 * p.dt);
  d.f1 = std::isnan(request.f1) ? d.f_lowest : request.f1;
  d.f2 = std::isnan(request.f2) ? std::min(d.f_highest, d.f_nyquist) : request.f2;
  if (std::isnan(request.f1) && std::isnan(request.f2) && !(d.f2 > d.f1))
    throw InputError("--rayleigh: the model's modes have one frequency (" +
                     format_digits(d.f1, 6) + " Hz); give two with --band F1:F2");
  if (!(d.f1 > 0) || !(d.f2 > d.f1) || !std::isfinite(d.f2))
    throw InputError("--band: needs 0 < F1 < F2 (got " + std::to_string(d.f1) + ":" +
                     std::to_string(d.f2) + " Hz)");
  d.zeta1 = request.zeta1;
  d.zeta2 = request.zeta2;
  std::tie(d.alpha, d.beta) = rayleigh_pair(d.f1, d.zeta1, d.f2, d.zeta2);
  d.feasible = d.alpha >= 0 && d.beta >= 0;
  // The spectrum and the asked band, and an octave either side to show the rise outside.
  const double lo = 0.5 * std::min(d.f_lowest, d.f1), hi = 2 * std::max(d.f_highest, d.f2);
  for (int k = 0; k <= 40; ++k) {
    const double f = lo * std::pow(hi / lo, k / 40.0);
    d.curve_f.push_back(f);
    d.curve_zeta.push_back(rayleigh_zeta(d.alpha, d.beta, f));
  }
  // External loads: the speed at which -alpha m_i v balances f_i.
  for (size_t i = 0; i < bare.mass.size(); ++i) {
    const double f = bare.spec().external_force[i].norm();
    if (bare.spec().fixed[i] || !(f > 0)) continue;
    ++d.forced_nodes;
    const double v = f / (d.alpha * bare.mass[i]);
    if (d.terminal_node < 0 || v > d.terminal_velocity) {
      d.terminal_node = static_cast<int>(i);
      d.terminal_velocity = v;
      d.terminal_velocity_with_gamma = f / (d.alpha * bare.mass[i] + bare.gamma[i]);
    }
  }
  if (!d.feasible) return d;
  Params q = p;
  q.rayleigh_mass = d.alpha;
  q.rayleigh_stiffness = d.beta;
  stage("stage 2 of 3: the largest stable beta at dt (a certified eigenvalue per probe)");
  d.beta_max =
      damping_kind_max(scene.model, x, q, DampingKind::rayleigh_stiffness, max_factor_flops);
  double rate = 0;
  if (commuting(bare, rate))
    d.beta_max_closed = (4 - d.lambda_max * p.dt * p.dt - 2 * p.dt * (rate + d.alpha)) /
                        (2 * p.dt * d.lambda_max);
  d.stable = d.beta < d.beta_max;
  stage("stage 3 of 3: the exact dt limit with the pair");
  const Model with_pair = compile_model(scene.model, q);
  d.dt_max = general_limits(with_pair, x, q, max_factor_flops).dt_max;
  d.zeta2_at_beta_max = rayleigh_zeta(d.alpha, d.beta_max, d.f2);
  d.zeta_highest_at_beta_max = rayleigh_zeta(d.alpha, d.beta_max, d.f_highest);
  return d;
}

}  // namespace dampbound
