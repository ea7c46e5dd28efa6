#pragma once
// Suggest stable values: for a dt, the damping range every applicable criterion
// accepts and the fastest-settling damping in it; for a damping, the largest stable dt. Each
// suggestion is verified by running it through a Session (the scene's perturbation and
// protocol). A core function so that the CLI (`dampbound suggest`) and the GUI share it.
// The algorithm is in docs/criteria.md, "suggest".
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/analysis/criteria.hpp"
#include "dampbound/run/protocol.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// A suggested parameter set and what running it through a Session gave.
struct VerifiedRun {
  std::string label;  ///< e.g. "fastest-settling gamma"
  Params params;
  RunResult result;   ///< judged by the settled rule (SPEC 8)
  StopRules rules;    ///< what judged it (the settled rule)
  /// A suggestion counts as verified only when its run settles (SPEC 8): a first entry
  /// followed by an exit, or a divergence, is not a verification.
  bool verified() const { return result.outcome == Outcome::settled; }
};

/// Nodes that share (m_i, kappa_i, gamma_scale_i): one line of the per-node ranges.
struct NodeClass {
  int count = 0;
  int example = 0;           ///< one node of the class
  double mass = 0, kappa = 0, gamma_scale = 0;
  double lower_bound = 0;    ///< eq. 5 for the class: 2 sqrt(m_i kappa_i)
  double gamma_min = 0;      ///< the accepted range of gamma_i = gamma * gamma_scale_i
  double gamma_max = 0;
  /// SPEC 9 at rest: the class's gamma_i is guaranteed stable in [lower_bound, safe_max)
  /// (safe_max = min gamma_safe_i over the class; below lower_bound when the class cannot be
  /// critically damped at this dt), and dt_safe is the largest dt at which gamma_i =
  /// lower_bound is guaranteed at every node of the class (s).
  double safe_max = 0;
  double dt_safe = 0;
};

struct SuggestOptions {
  bool verify = true;        ///< run each suggestion through a Session
  int trials = 16;           ///< non-uniform rates: first-pass trial runs for the best gamma
  int threads = 1;           ///< the exact analysis's threads (ExactOptions::threads)
  /// ExactOptions::max_factor_flops. Over it the suggestions come from what is proved
  /// without a factorisation (ExactStability::unfactored; `proved_only` below), and where
  /// that proves no stable range: std::runtime_error.
  double max_factor_flops = std::numeric_limits<double>::infinity();
  /// Called before each stage of a call (the exact analysis, each trial run, each verifying
  /// run) with the stages done, the stages known so far (the total grows once the trial runs
  /// are decided) and what runs next; returning false stops the call with SuggestCancelled.
  std::function<bool(int done, int total, const std::string& next)> progress;
  /// ExactOptions::shared: one certified spectrum and pattern analysis for the call's exact
  /// analyses of one model (the scene's gamma and gamma_min; the substep count), and for the
  /// caller's calls after (null: each computes its own).
  std::shared_ptr<SharedAnalysis> shared = nullptr;
};

/// What suggest_damping and suggest_step throw when SuggestOptions::progress asks them to stop.
struct SuggestCancelled : std::runtime_error {
  SuggestCancelled() : std::runtime_error("suggest: cancelled") {}
};

/// For params.dt: the range of the user's gamma that eq. 5 (gamma_i >= 2 sqrt(m_i kappa_i) at
/// every node) and the exact linear analysis of params.integrator both accept, the
/// dt-only criteria's verdicts, and the fastest-settling gamma in the range.
struct DampingSuggestion {
  double dt = 0;
  double gamma_min = 0;          ///< max(eq. 5 over nodes / gamma_scale_i, exact gamma_lo)
  double gamma_max = 0;          ///< the exact gamma_hi (exclusive)
  double safe_max = 0;           ///< SPEC 9: the user's gamma < safe_max guarantees stability
                                 ///< (<= 0: none, some gamma_safe_i <= 0 at this dt)
  std::string min_by, max_by;    ///< the criterion that sets each end
  bool empty = true;             ///< gamma_min >= gamma_max: no damping satisfies all
  std::vector<CriterionResult> dt_only;  ///< Delingette, Provot, Kacic-Alesic at this dt
  bool dt_accepted = true;       ///< every dt-only criterion accepts this dt
  std::vector<NodeClass> classes;
  double gamma_best = 0;         ///< fastest settling in [gamma_min, gamma_max)
  std::string best_method;       ///< "min spectral radius" or "fewest iterations in trials"
  double best_rho = 0;           ///< spectral radius at gamma_best (NaN when from trials)
  double dt_max_at_gamma_min = 0;  ///< when empty: the largest dt stable at gamma_min
  std::vector<VerifiedRun> runs;   ///< best, and the two ends (gamma_min, 0.99 gamma_max)
  ExactStability exact;
  /// Over the factorisation budget (exact.computed() false): the range is what is proved
  /// stable without a factorisation, gamma_max included (Gershgorin on SPEC 7's index matrix
  /// for the paper's step, every mode in [0, Gershgorin's bound] for the others), and
  /// dt_max_at_gamma_min the largest dt proved so. The exact upper limit lies in
  /// [gamma_max, gamma_unstable_from) (the paper's step; NaN for the others). gamma_best,
  /// where rates are uniform, minimises the largest radius over every lambda in
  /// [SPEC 9's floor, Gershgorin's bound], which holds the spectrum, so best_rho is an upper
  /// bound; NaN where the floor is 0 (the slowest mode is unknown).
  bool proved_only = false;
  double gamma_unstable_from = std::numeric_limits<double>::quiet_NaN();
};

/// For params.gamma: the largest stable dt of params.integrator (exact), the largest dt that
/// every criterion accepts (exact, Provot, Kacic-Alesic, Delingette), each verified.
struct StepSuggestion {
  double gamma = 0;
  double dt_exact = 0;           ///< exact limit (exclusive)
  double dt_all = 0;             ///< min over all dt criteria (the recommendation)
  double dt_safe = 0;            ///< SPEC 9: min over free nodes of dt_safe_i at gamma_i (s)
  int dt_safe_node = -1;         ///< the node that sets it
  std::string dt_all_by;         ///< the criterion that sets it
  std::vector<VerifiedRun> runs;  ///< at 0.99 dt_exact and at dt_all
  ExactStability exact;
  /// Over the factorisation budget: dt_exact is the largest dt proved stable without a
  /// factorisation (included), and the exact limit lies in [dt_exact, dt_unstable_from).
  bool proved_only = false;
  double dt_unstable_from = std::numeric_limits<double>::quiet_NaN();
};

DampingSuggestion suggest_damping(const SceneSpec& scene, const Params& params,
                                  const StopRules& rules, const SuggestOptions& options = {});
StepSuggestion suggest_step(const SceneSpec& scene, const Params& params, const StopRules& rules,
                            const SuggestOptions& options = {});

/// Runs one parameter set through a Session with `rules` under the settled rule (SPEC 8),
/// whatever rules.rule says (policy fixed as given).
VerifiedRun verify_run(const SceneSpec& scene, const Params& params, const StopRules& rules,
                       const std::string& label);

}  // namespace dampbound
