#pragma once
// Rayleigh damping from the model's own spectrum (docs/criteria.md, "Rayleigh damping from the
// spectrum"). SPEC 10's Rayleigh damping gives the mode of angular frequency w = sqrt(lambda)
// (lambda an eigenvalue of M^-1 K) the ratio
//   zeta(w) = (alpha + beta w^2) / (2 w) = alpha / (2 w) + beta w / 2,
// so asking zeta_1 at w_1 and zeta_2 at w_2 is two linear equations in (alpha, beta):
//   alpha = 2 w_1 w_2 (zeta_1 w_2 - zeta_2 w_1) / (w_2^2 - w_1^2),
//   beta  = 2 (zeta_2 w_2 - zeta_1 w_1) / (w_2^2 - w_1^2).
// The pair is then judged at the scene's dt by SPEC 10's exact index (the scene's nodal damping
// and dashpots held), and by the closed forms where C^ commutes with A.
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/analysis/damping_limits.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// What is asked: ratios at two frequencies (Hz); NaN frequencies take the defaults.
struct RayleighRequest {
  double zeta1 = 0.05, zeta2 = 0.05;
  double f1 = std::numeric_limits<double>::quiet_NaN();  ///< default: the lowest mode
  double f2 = std::numeric_limits<double>::quiet_NaN();  ///< default: the highest the step resolves
};

/// zeta at frequency f (Hz) of the pair (alpha in 1/s, beta in s).
double rayleigh_zeta(double alpha, double beta, double f);
/// The pair giving zeta1 at f1 and zeta2 at f2 (Hz, f1 != f2), the formulas above.
std::pair<double, double> rayleigh_pair(double f1, double zeta1, double f2, double zeta2);

struct RayleighDesign {
  double lambda_min = 0, lambda_max = 0;  ///< lowest non-zero and highest eigenvalue of M^-1 K
  double f_lowest = 0, f_highest = 0;     ///< their frequencies sqrt(lambda) / (2 pi) (Hz)
  double f_nyquist = 0;                   ///< 1 / (2 dt): the highest frequency a step resolves
  double f1 = 0, f2 = 0, zeta1 = 0, zeta2 = 0;  ///< what was asked (defaults filled in)
  double alpha = 0, beta = 0;             ///< the pair (may be negative: see `feasible`)
  bool feasible = false;                  ///< alpha >= 0 and beta >= 0
  /// At the scene's dt with the scene's nodal damping and dashpots, alpha held: the step is
  /// stable for beta in [0, beta_max) (SPEC 10's exact index; 0: alpha alone is unstable).
  double beta_max = 0;
  /// SPEC 10's closed form (4 - lambda_max dt^2 - 2 dt (gamma/m + alpha)) / (2 dt lambda_max)
  /// where C^ commutes with A (no dashpot, gamma_i / m_i uniform); NaN elsewhere.
  double beta_max_closed = std::numeric_limits<double>::quiet_NaN();
  bool stable = false;                    ///< feasible and beta < beta_max
  double dt_max = 0;                      ///< the exact dt limit with the pair (s)
  /// With beta_max instead of beta (alpha held): the ratios it reaches at f2 and at the
  /// highest mode.
  double zeta2_at_beta_max = 0, zeta_highest_at_beta_max = 0;
  /// External forces: |f_i| / (alpha m_i), the speed at which the mass term alone balances
  /// the load (cm/s), its largest value and node (-1: no force), and |f_i| / (alpha m_i +
  /// gamma_i) at that node with the nodal damping too.
  int forced_nodes = 0;
  int terminal_node = -1;
  double terminal_velocity = 0, terminal_velocity_with_gamma = 0;
  /// zeta(f) at 41 frequencies log-spaced over [min(f_lowest, f1) / 2, 2 max(f_highest, f2)].
  std::vector<double> curve_f, curve_zeta;
};

/// Designs the pair on the scene's model at params (its dt, gamma and kd; its own alpha and
/// beta are replaced), linearised at rest. Throws InputError for a bad request (ratios not
/// positive, f1 >= f2, a model with no non-zero mode) or an integrator other than the paper's.
/// `progress`, when given, is called before each stage (the spectrum, the largest stable beta,
/// the dt limit) with what runs next; returning false stops the call with SuggestCancelled
/// (suggest.hpp; the tuner's Cancel). `max_factor_flops`: as general_limits
/// (damping_limits.hpp), FactorisationOverBudget before any factorisation over it.
RayleighDesign rayleigh_from_spectrum(const SceneSpec& scene, const Params& params,
                                      const RayleighRequest& request,
                                      const std::function<bool(const std::string&)>& progress = {},
                                      double max_factor_flops = kUnboundedFactor);

}  // namespace dampbound
