#pragma once
// The exact linear stability of one model, state and parameters, for any integrator
// (SPEC 7): lambda range of M^-1 K, the spectral radius of the step, the interval of
// the user's gamma that keeps the step stable at dt, and the largest stable dt at gamma.
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/damping_limits.hpp"
#include "core/analysis/linear_stability_modes.hpp"
#include "dampbound/analysis/linear_stability.hpp"

namespace dampbound {

class SharedAnalysis;

/// How the numbers were obtained (docs/criteria.md, "Exact linear stability").
enum class ExactMethod {
  per_mode,           ///< gamma_i/m_i uniform: modes decouple; closed form or per-mode 2x2
  symmetric_index,    ///< semi-implicit, non-uniform: lambda_max(dt^2 A + 2 dt C) < 4
  unconditional,      ///< implicit Euler: stable for every dt > 0 and gamma >= 0
  frozen_estimate,    ///< other explicit steps, non-uniform: limits from the worst uniform
                      ///< rate in [c_min, c_max] (an estimate); verdict from Arnoldi's rho
  damped_radius,      ///< forward Euler, Verlet, RK4 with SPEC 10's dashpot or Rayleigh
                      ///< damping: the verdict from the spectral radius of the step with the
                      ///< whole damping; the gamma interval and dt limit are not computed (NaN)
  over_budget,        ///< not computed: one factorisation would exceed the budget
                      ///< (ExactOptions::max_factor_flops); every number is NaN
};

const char* to_string(ExactMethod m);

struct ExactStability {
  Integrator integrator = Integrator::semi_implicit_euler;
  ExactMethod method = ExactMethod::per_mode;
  bool uniform_rate = true;   ///< gamma_i/m_i equal over the free nodes
  double rate_min = 0;        ///< min and max of gamma_i/m_i over the free nodes (1/s)
  double rate_max = 0;
  StiffnessSpectrum spectrum;  ///< of M^-1 K at the state (1/s^2); decides stability
  /// lambda_max lies in [lambda_max_lo, spectrum.lambda_max] (1/s^2): the upper end is
  /// certified by a Cholesky factorisation, the lower by a Rayleigh quotient.
  double lambda_max_lo = 0;
  /// lambda_min lies in [spectrum.lambda_min, lambda_min_hi] (1/s^2): the lower end is
  /// certified by a factorisation (or SPEC 9's floor), the upper is a Rayleigh quotient.
  double lambda_min_hi = 0;
  /// The spectrum without zero modes (lambda = 0: motions no spring resists, e.g. the two-node
  /// system's transverse directions), whose z = 1 neither grows nor decays whatever gamma and
  /// dt. The spectral radius (the decay rate per step) is taken over it.
  StiffnessSpectrum decaying;
  bool zero_modes = false;
  /// K is indefinite at the state: some vector's Rayleigh quotient is below
  /// -kZeroModeTolerance lambda_max (compressed springs can do it; SPEC 9). That mode grows
  /// under every explicit step whatever gamma and dt (its characteristic polynomial is
  /// negative at z = 1), so their gamma interval is empty and dt_max 0. Implicit Euler damps
  /// such a mode only at a long enough step; its limits are then NaN (not computed) and the
  /// verdict is the spectral radius.
  bool indefinite = false;
  double spectral_radius = 0;  ///< rho of one step at the user's gamma and dt (NaN: not computed)
  bool radius_converged = true;
  double index = 0;           ///< symmetric_index only: lambda_max(dt^2 A + 2 dt C); stable < 4
  /// SPEC 10: the model has dashpot or Rayleigh damping and the step is the paper's; the
  /// limits, index and verdict are the generalised index's (general_limits), the nodal
  /// spectral radius is not computed (NaN).
  bool spec10 = false;
  /// spec10 only: general_limits' result as computed (its gamma_max not clamped at 0), for
  /// callers that print SPEC 10's lines without computing it again.
  GeneralLimits general;
  bool stable = false;        ///< rho <= 1 (bounded; rho = 1 is marginal: no decay); over
                              ///< the budget only where proved without one (Unfactored)
  double gamma_lo = 0;        ///< the user's gamma (gamma_i = gamma * gamma_scale_i) is stable
  double gamma_hi = 0;        ///< at params.dt for gamma_lo <= gamma < gamma_hi (hi may be inf)
  double dt_max = 0;          ///< the largest stable dt at the user's gamma (may be inf)
  /// Per mode (uniform rates) only; NaN otherwise. The radius, `stable` and the limits above
  /// are taken over the spectrum's certified outer ends [lambda_min, lambda_max], which
  /// guarantees them; these are the same numbers over its inner ends [lambda_min_hi,
  /// lambda_max_lo], and the true ones lie between. The two agree to about 1e-10 where the
  /// certificates hold; where one fails (a cluster shift-and-invert cannot split, docs/
  /// criteria.md) an end is only bracketed, and the criteria show both (criteria.cpp).
  struct Inner {
    double spectral_radius = std::numeric_limits<double>::quiet_NaN();
    double gamma_lo = std::numeric_limits<double>::quiet_NaN();
    double gamma_hi = std::numeric_limits<double>::quiet_NaN();
    double dt_max = std::numeric_limits<double>::quiet_NaN();
    bool stable = false;
  } inner;
  /// over_budget only: CHOLMOD's prediction for one factorisation and the budget it exceeds,
  /// and one line saying so (FactorisationOverBudget's text).
  double factor_flops = 0, factor_bytes = 0, factor_budget = 0;
  std::string not_computed_reason;
  /// over_budget only: what plain Lanczos and Gershgorin prove without a factorisation
  /// (docs/criteria.md, "Over the factorisation budget"); NaN where not tried
  /// (ExactOptions::unfactored_steps = 0).
  struct Unfactored {
    /// lambda_max of M^-1 K lies in [lambda_max_lo, lambda_max_hi] (1/s^2): a Rayleigh
    /// quotient less its rounding, and the lower of Gershgorin's bound (SPEC 9's largest R_i,
    /// also kept in `gershgorin`) and the node-block splitting's (splitting_ceilings).
    double lambda_max_lo = std::numeric_limits<double>::quiet_NaN();
    double lambda_max_hi = std::numeric_limits<double>::quiet_NaN();
    double gershgorin = std::numeric_limits<double>::quiet_NaN();
    /// Where A's own top is local: the nodes of the patch around it (detail/index_patch.hpp at
    /// gamma 0, dt 1) that narrowed [lambda_max_lo, lambda_max_hi]; 0 where none did.
    int lambda_patch_nodes = 0;
    /// The paper's step only: the index lambda_max(dt^2 A + 2 dt C) at the user's gamma and
    /// dt is at least this (>= 4 proves the step unstable), and with the same vector every
    /// gamma >= gamma_unstable_from (at dt) and every dt >= dt_unstable_from (at gamma) is
    /// proved unstable; inf: that vector proves nothing there.
    double index_at_least = std::numeric_limits<double>::quiet_NaN();
    /// The paper's step with K >= 0 proved (SPEC 9's floor): the index is at most this, the
    /// lower of Gershgorin on its rows (SPEC 9's safe bound, also kept in
    /// `index_gershgorin`) and the node-block splitting (splitting_ceilings); below 4 it
    /// proves the step stable (`stable`), and dt_stable_up_to and gamma_stable_lo/hi below
    /// give the dts and gammas either bound proves. NaN otherwise.
    double index_at_most = std::numeric_limits<double>::quiet_NaN();
    double index_gershgorin = std::numeric_limits<double>::quiet_NaN();
    /// The paper's step where the index's top is local: the nodes of the patch around it
    /// (detail/index_patch.hpp; 0: none), whose principal submatrix's top vector also proves
    /// the instability thresholds below where it proves more than Lanczos's, and, with
    /// K >= 0, the index's upper bound from the patch (NaN where it proved less than the
    /// node-by-node bounds; otherwise index_at_most) and the stable gamma and dt it proves.
    int patch_nodes = 0;
    double index_patch = std::numeric_limits<double>::quiet_NaN();
    double gamma_unstable_from = std::numeric_limits<double>::quiet_NaN();
    double dt_unstable_from = std::numeric_limits<double>::quiet_NaN();
    /// Forward Euler, Verlet and RK4 at uniform gamma/m (mode_instability; RK4 has no
    /// gamma or dt threshold, those stay NaN): every mode with
    /// lambda >= mode_unstable_from is unstable at the user's gamma and dt, so
    /// lambda_max_lo >= it proves the step unstable; with lambda_max_lo every gamma <=
    /// gamma_unstable_below (at dt; -inf: none; inf: every gamma, when no node has damping)
    /// and every dt >= dt_unstable_from (at gamma) is proved unstable. NaN otherwise.
    double mode_unstable_from = std::numeric_limits<double>::quiet_NaN();
    double gamma_unstable_below = std::numeric_limits<double>::quiet_NaN();
    /// The stable side when SPEC 9's floor proves K >= 0. Forward Euler, Verlet and RK4 at
    /// uniform gamma/m (mode_stability): every mode lies in [0, stable_lambda_hi]
    /// (lambda_max_hi, raised by 1e-12 of itself for its sums' rounding). Those and the
    /// paper's step (index_at_most, any rates): every dt <= dt_stable_up_to (at gamma) and
    /// every gamma in [gamma_stable_lo, gamma_stable_hi] (at dt; none when lo > hi) is proved
    /// stable, and `stable` says whether the user's are (RK4's gamma range is the one around
    /// the user's gamma, or where that is not proved the nearest one found, which leaves the
    /// user's gamma outside). NaN otherwise.
    double stable_lambda_hi = std::numeric_limits<double>::quiet_NaN();
    double dt_stable_up_to = std::numeric_limits<double>::quiet_NaN();
    double gamma_stable_lo = std::numeric_limits<double>::quiet_NaN();
    double gamma_stable_hi = std::numeric_limits<double>::quiet_NaN();
    int lanczos_steps = 0;  ///< of one of the two Lanczos runs (the second replays the first)
    /// Implicit Euler with K proved positive semidefinite (SPEC 9's floor, no spring
    /// compressed): stable for every dt and gamma, which needs no lambda_max (then `stable`).
    bool unconditional = false;
  } unfactored;
  bool computed() const { return method != ExactMethod::over_budget; }
  const std::string& over_budget_reason() const { return not_computed_reason; }
};

/// |lambda| at most this times lambda_max counts as a zero mode (z = 1: neither grows nor
/// decays); a certified lambda_min below -kZeroModeTolerance lambda_max makes K indefinite.
inline constexpr double kZeroModeTolerance = 1e-9;

/// Options: the spectral radius of a non-uniform mesh costs an Arnoldi run (up to seconds);
/// `with_radius = false` skips it where only limits are wanted (spectral_radius = NaN).
struct ExactOptions {
  bool with_radius = true;
  /// Threads for the eigenvalue solver's Lanczos products (0: one per CPU). The results are
  /// the same bits on any count; 1 suits callers that already keep the cores busy.
  int threads = 1;
  /// The most floating-point operations one sparse factorisation may take (CHOLMOD's
  /// prediction, known after the pattern analysis and before any factorisation); above it
  /// nothing is factorised and the result's method is over_budget. Infinite: no limit.
  /// The command line and the tuner use kDefaultFactorBudget.
  double max_factor_flops = std::numeric_limits<double>::infinity();
  /// Over the budget: the most Lanczos steps of the bounds proved without a factorisation
  /// (ExactStability::unfactored; two runs of up to this many matrix-vector products; their
  /// cost on big meshes: docs/performance.md). 0: none.
  int unfactored_steps = 40;
  /// The spectrum and pattern analysis shared with the calls before on the same model
  /// (shared_analysis.hpp): the same results, without certifying the same spectrum twice.
  std::shared_ptr<SharedAnalysis> shared = nullptr;
};

/// The command line's and the tuner's budget: 200 GFlop per factorisation. Every plane up to
/// 1M nodes fits (1M: ~160 GFlop); tetrahedral blocks up to ~40k nodes (27k: 79 GFlop; 97k:
/// 940 GFlop). What it costs in seconds: docs/performance.md.
inline constexpr double kDefaultFactorBudget = 2e11;

/// The analysis at positions x for the model (set_params(params) done) and params.dt,
/// params.integrator, with the user's gamma_i = model.gamma[i] held fixed (policy fixed).
ExactStability exact_stability(const Model& model, const std::vector<Vec3>& x,
                               const Params& params, const ExactOptions& options = {});

/// The same analysis on assembled matrices (what linear_limits.hpp serves a user's own K
/// with): A = M^-1/2 K M^-1/2 over the free dofs, R the damping rate per dof per unit of
/// params.gamma (gamma_i / (params.gamma m_i)), `floor` a proved lower bound on A's smallest
/// eigenvalue where one is known (SPEC 9's, psd_floor), else nullopt. No model: over the
/// factorisation budget it throws FactorisationOverBudget.
ExactStability exact_stability(const SparseMatrix& A, const Eigen::VectorXd& R,
                               std::optional<double> floor, const Params& params,
                               const ExactOptions& options = {});

/// Spectral radius of the step at the user's gamma scaled by `gamma / params.gamma`
/// (gamma_i = gamma * gamma_scale_i), everything else as in `exact`. Exact per mode when the
/// rate is uniform, Arnoldi otherwise.
SpectralRadius spectral_radius_at(const Model& model, const SparseMatrix& K_weighted,
                                  const ExactStability& exact, const Params& params,
                                  double gamma);

}  // namespace dampbound
