#pragma once
// The safe bound of SPEC 9 applied to a sweep's rows: the check per trial at rest, the
// confusion of the paper's runtime check and the safe check as predictors of divergence
// under fixed damping, and what the safe policy promises.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/sweep/csv.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// A scene's R_i (SPEC 9) at rest at m = kappa = 1, with the nodes' scales: the stiffness
/// part A scales as kappa/m (K ~ kappa, M ~ m), so R_i(m, kappa) = row_sum_i kappa/m.
struct SafeUnit {
  std::vector<double> mass_scale, gamma_scale, row_sum;  ///< free nodes only; row_sum 1/s^2
};
SafeUnit unit_safe_bound(const SceneSpec& scene);

/// The edge of the safe check at rest along one parameter, the others as given: the largest
/// gamma, the smallest m, the largest kappa or the largest dt (units as in Params) at which
/// every free node has gamma * gamma_scale_i < gamma_safe_i, each node's condition
/// gamma gs_i < 2 m ms_i / dt - ms_i dt R_i kappa / 2 solved for that parameter. NaN where no
/// positive value satisfies it (or the parameter does not appear).
enum class SafeAxis { m, kappa, gamma, dt };
double safe_edge(const SafeUnit& u, SafeAxis axis, double m, double kappa, double gamma, double dt);

/// The safe check at rest: gamma * gamma_scale_i < gamma_safe_i at every free node.
bool safe_at_rest(const SafeUnit& u, double m, double kappa, double gamma, double dt);
/// The safe policy's guarantee at rest: gamma_safe_i > 0 at every free node (dt below every
/// 2/sqrt(R_i)), so that some damping keeps the linearised step stable.
bool safe_policy_guaranteed(const SafeUnit& u, double m, double kappa, double dt);

/// Predicting divergence: positive = the predictor says "will diverge".
struct Confusion {
  std::uint64_t true_pos = 0, false_pos = 0, false_neg = 0, true_neg = 0;
};
struct PredictorScore {
  std::string predictor;
  Confusion c;
};

/// Under fixed damping: the paper's runtime check (some node-step with gamma_lo > gamma_hi,
/// sec. 5), the safe check at rest (SPEC 9) and, when lambda_unit is finite, the exact linear
/// limit at rest (SPEC 7), each against the trial's outcome (diverged or not).
std::vector<PredictorScore> divergence_confusion(const std::vector<SweepRow>& rows,
                                                 const SafeUnit& unit, double lambda_unit);

/// A markdown table of divergence_confusion.
std::string confusion_markdown(const std::vector<PredictorScore>& scores);

/// Summary lines for `sweep` and `reproduce`: under policy fixed the confusion table; under
/// policy safe how many trials diverged where the policy guarantees stability at rest and
/// where it cannot (gamma_safe_i <= 0 somewhere), naming the first few of each.
std::vector<std::string> safe_summary_lines(const std::vector<SweepRow>& rows,
                                            std::optional<DampingPolicy> policy, const SafeUnit& unit,
                                            double lambda_unit);

/// The `reproduce` report's section "What guarantees stability" (markdown): the safe bound
/// on the scene, the confusion table of the checks on a fixed-damping sweep, and the same
/// grid's outcomes under the safe policy with what it promised.
std::string safe_report_section(const std::vector<SweepRow>& fixed_rows,
                                const std::string& fixed_definition,
                                const std::vector<SweepRow>& safe_rows,
                                const std::string& safe_definition, const SafeUnit& unit,
                                double lambda_unit);

}  // namespace dampbound
