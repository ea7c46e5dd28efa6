#pragma once
// How often the paper's predictions, and the exact linear limits of SPEC 7, held on a sweep.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/sweep/csv.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// lambda_max of M^-1 K at rest with m = kappa = 1 (1/s^2). M^-1 K scales with kappa/m, so
/// lambda_max(m, kappa) = this * kappa/m for any trial of the scene.
double unit_stiffness_eigenvalue(const SceneSpec& scene);

/// SPEC 7 for uniform gamma/m: the step is linearly stable about rest iff
/// 0 < gamma dt/m < 2 and lambda_max dt^2 < 4 - 2 gamma dt/m, i.e.
/// gamma < gamma_max = 2 m/dt - m lambda_max dt/2 (gamma = 0 is marginal: not unstable).
bool linearly_unstable(double m, double kappa, double gamma, double dt, double lambda_unit);

/// SPEC 10: the dashpots' damping matrix at rest is `ratio * kd / kappa` times K when every
/// spring is at its rest length there and kd_scale / kappa_scale (springs) and
/// anchor_kd_scale / anchor_scale (anchors) are all one ratio; nullopt otherwise.
std::optional<double> dashpot_stiffness_ratio(const SceneSpec& scene);

/// SPEC 10's closed form for a uniform model: with alpha, beta and dashpots proportional to K
/// (`dashpot_ratio`, see above) every mode has the rate c(lambda) = gamma/m + alpha +
/// (beta + ratio kd/kappa) lambda, and the step is linearly unstable about rest iff
/// spec7_unstable(lambda_max, c(lambda_max), dt) (both conditions grow with lambda). Rows
/// without SPEC 10 damping give linearly_unstable() above.
bool linearly_unstable(const SweepRow& row, double lambda_unit, double dashpot_ratio);

/// A row with dashpot or Rayleigh damping (SPEC 10).
inline bool has_spec10_damping(const SweepRow& r) {
  return r.kd != 0 || r.rayleigh_mass != 0 || r.rayleigh_stiffness != 0;
}

/// One prediction: "condition => expected outcome" held in `held` of `of` trials.
struct PredictionCheck {
  std::string claim;
  std::uint64_t held = 0;
  std::uint64_t of = 0;
};

/// The checks that apply to the sweep's policy: for fixed damping the paper's lower bound
/// (zeta < 1 => not restored, zeta >= 1 => restored) and the exact linear limit (unstable =>
/// diverged, stable => not diverged); for policy upper the paper's Fig. 2 claims (factor 1 =>
/// restored, factor > 1 => diverged); for lower and clamp "within the bounds => restored";
/// none for safe or an unknown policy (nullopt).
/// Rows with dashpots are checked against the exact limit only with a `dashpot_ratio`.
std::vector<PredictionCheck> check_predictions(const std::vector<SweepRow>& rows,
                                               std::optional<DampingPolicy> policy, double lambda_unit,
                                               std::optional<double> dashpot_ratio = std::nullopt);

/// "key=value" out of a header definition ("policy", "max-iter", ...); nullopt when absent.
std::optional<std::string> definition_value(const std::string& definition,
                                            const std::string& key);

/// The rule a sweep's rows were judged by (SPEC 8): settled when any row is settled or
/// not_settled, else first-entry.
StopRule rows_rule(const std::vector<SweepRow>& rows);

/// How often the settled rule overturned the paper's verdict (SPEC 8): of the trials that
/// entered the band (first-entry: restored), those that did not settle.
struct Overturned {
  std::uint64_t entered = 0;   ///< trials with a first entry (the paper's restored)
  std::uint64_t left = 0;      ///< ... then not settled at the limit
  std::uint64_t diverged = 0;  ///< ... then diverged
};
Overturned count_overturned(const std::vector<SweepRow>& rows);

/// The lines printed after a sweep: outcome counts (under the settled rule also the number of
/// first-entry verdicts it overturned) and the prediction checks.
std::vector<std::string> summary_lines(const std::vector<SweepRow>& rows,
                                       std::optional<DampingPolicy> policy, double lambda_unit,
                                       std::optional<double> dashpot_ratio = std::nullopt);

}  // namespace dampbound
