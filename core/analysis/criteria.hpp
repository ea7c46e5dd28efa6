#pragma once
// Every stability criterion side by side (SPEC 7): the paper's bounds (eqs. 5, 6,
// sec. 5), the classic criteria the paper cites (Delingette [11], Provot [2],
// Kacic-Alesic [12]) and the exact linear analysis of the chosen integrator, each computed
// for a model, a state and the parameters, with its verdict. docs/criteria.md has the table.
#include <string>
#include <vector>

#include "core/analysis/linear_stability_exact.hpp"
#include "dampbound/physics/model.hpp"

namespace dampbound {

enum class CriterionVerdict {
  within,          ///< the criterion accepts the parameters
  beyond,          ///< the criterion rejects them
  not_applicable,  ///< it does not speak to this case (e.g. eq. 6 at rest, v = 0)
};

const char* to_string(CriterionVerdict v);
/// within when `ok`, else beyond: a criterion that always speaks to the case.
inline CriterionVerdict verdict_of(bool ok) {
  return ok ? CriterionVerdict::within : CriterionVerdict::beyond;
}

/// One criterion evaluated: its quantity, what it is compared with, and the verdict.
struct CriterionResult {
  std::string name;     ///< e.g. "Provot natural period"
  std::string source;   ///< e.g. "Provot 1995 (paper ref. [2]), SPEC 7"
  std::string formula;  ///< e.g. "T0 = pi sqrt(m_i / kappa_i), require dt < T0"
  double value = 0;     ///< the criterion's quantity (T0, k_c, a bound, lambda_max, ...)
  std::string unit;     ///< "s", "mass unit/s", "1/s^2", ...
  std::string test;     ///< the comparison made, with numbers, e.g. "dt = 0.05 < T0 = 3.14"
  CriterionVerdict verdict = CriterionVerdict::not_applicable;
  int node = -1;        ///< the worst node where the criterion is per node, else -1
};

/// Delingette [11]: critical stiffness k_c = m_total / (n pi^2 dt^2) over the free nodes
/// (mass unit/s^2). Beyond k_c the explicit system diverges (a heuristic estimate).
double delingette_critical_stiffness(double m_total, int n, double dt);

/// Provot [2]: natural period T0 = pi sqrt(m / kappa) (s); dt < T0 is required.
double provot_natural_period(double m, double kappa);

/// Kacic-Alesic [12] (Verlet): largest step 2 sqrt(m / K) (s), K the combined stiffness.
double kacic_alesic_dt(double m, double K);

/// K_i of Kacic-Alesic: the sum of the stiffness of every spring and anchor at node i.
std::vector<double> combined_stiffness(const Model& model);

/// The classic criteria (Delingette, Provot, Kacic-Alesic) for the model (set_params done)
/// and params.dt; per-node ones report their worst free node.
std::vector<CriterionResult> classic_criteria(const Model& model, const Params& params);

/// The paper's criteria: eq. 5 (worst node: smallest gamma_i - gamma_lo_i), eq. 6 at the
/// state (x, v) (worst node: smallest gamma_hi_i - gamma_i; not applicable where every
/// v_i = 0) and the sec. 5 check (nodes with gamma_lo_i > gamma_hi_i). The user's gamma_i
/// (policy fixed) is judged.
std::vector<CriterionResult> paper_criteria(const Model& model, const State& state,
                                            const Params& params);

/// The exact linear analysis as criteria: lambda_max (and lambda_min) of M^-1 K, the
/// spectral radius of the step, the exact gamma interval and the dt limit of the integrator.
std::vector<CriterionResult> exact_criteria(const ExactStability& exact, const Params& params);

/// Where `exact` was not computed (over the factorisation budget), how each exact row's test
/// begins: "not computed: " and why. The rest of the test (after "; ") is what Lanczos and
/// Gershgorin prove without a factorisation; the tuner states the reason once and shows each
/// row's rest.
std::string over_budget_test(const ExactStability& exact);

/// All of the above, in the order the `bounds` command prints them.
std::vector<CriterionResult> all_criteria(const Model& model, const State& state,
                                          const Params& params, const ExactStability& exact);

/// The system of the paper's derivation (sec. 2): node 0 fixed at the origin, node 1 free at
/// (1, 0, 0) cm on one spring of rest length 1 cm; no anchors. set_params(params) applied.
Model two_node_system(const Params& params);

/// One free node on a zero-rest-length anchor of stiffness kappa: the single oscillator.
Model single_node_system(const Params& params);

}  // namespace dampbound
