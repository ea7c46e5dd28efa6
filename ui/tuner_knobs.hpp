#pragma once
// The Suggest tab's other knobs (issue 67, docs/gui.md "Stiffness ceiling and Rayleigh pair"):
// the stiffness ceiling (core/analysis/kappa_ceiling.hpp, `suggest --kappa-max`: the largest
// factor on every spring and anchor that keeps the step stable at this dt and damping, with
// its runs at 0.98x and 1.02x) and the Rayleigh pair from the spectrum
// (core/analysis/rayleigh_design.hpp, `suggest --rayleigh Z`), computed on a worker thread
// with progress and Cancel as Suggest has, for the mesh as it is now (its cuts count). A
// result speaks for the parameters and the springs it was computed for: knobs_current() says
// whether it still does (the tab drops it on a parameter change, a Reset, a cut or another
// scene).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/analysis/kappa_ceiling.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/rayleigh_design.hpp"
#include "dampbound/run/session.hpp"
#include "ui/background_job.hpp"

namespace dampbound::ui {

/// The margin the apply button keeps below the ceiling: kappa times 0.98 x the factor (the
/// ceiling's own verifying run is at 0.98x, so the applied stiffness is the one that ran).
inline constexpr double kCeilingMargin = 0.98;
/// The damping ratio the Rayleigh pair asks at both ends of the band by default.
inline constexpr double kDefaultRayleighZeta = 0.05;

/// What one computation produced, and for which parameters and mesh.
struct KnobsResult {
  Params params;          ///< the parameters it was computed for
  int springs_cut = 0;    ///< springs cut away before (by hand or by the scene)
  double zeta = 0;        ///< the ratio asked of the pair at both ends of the band
  StiffnessCeiling ceiling;         ///< every spring and anchor (valid when ceiling_error is "")
  std::string ceiling_error;        ///< why there is no ceiling (another integrator, K not PSD)
  std::optional<RayleighDesign> rayleigh;  ///< the pair (none: rayleigh_error says why)
  std::string rayleigh_error;
};

/// The same values of every parameter the ceiling, the pair or their runs depend on.
bool same_model_params(const Params& a, const Params& b);

class TunerKnobs {
 public:
  /// Starts the computation for the mesh the session has now (its cuts count), its parameters
  /// and rules, asking the pair for `zeta` at the lowest mode and at the highest the step
  /// resolves; `generation`, `topology`: the tuner's counters, what knobs_current() compares.
  /// Ignored while one runs.
  void start(const Session& session, double zeta, std::uint64_t generation,
             std::uint64_t topology);
  /// The same for a scene as given (tests).
  void start(const SceneSpec& scene, const Params& params, const StopRules& rules, double zeta);
  BackgroundJob<KnobsResult>& job() { return job_; }
  const BackgroundJob<KnobsResult>& job() const { return job_; }
  /// The most one factorisation of the next start() may cost (flops; --factor-budget): over
  /// it the ceiling or the pair is the budget's one-line error.
  void set_factor_budget(double flops) { factor_budget_ = flops; }
  /// True while the last start() (running or finished) speaks for the tuner's model: the same
  /// parameters, and no reset, cut or scene since (`generation`, `topology` as Tuner counts
  /// them). The tab drops what is not.
  bool current(const Params& now, std::uint64_t generation, std::uint64_t topology) const {
    return same_model_params(params_, now) && generation_ == generation && topology_ == topology;
  }

 private:
  void launch(std::shared_ptr<const SceneSpec> scene, std::shared_ptr<const Model> model,
              int iteration, const Params& params, const StopRules& rules, double zeta, int cut);
  BackgroundJob<KnobsResult> job_;
  double factor_budget_ = kDefaultFactorBudget;
  Params params_;
  std::uint64_t generation_ = 0, topology_ = 0;
};

/// `current` with kappa = kCeilingMargin x the ceiling's factor x the kappa it was computed at
/// (the factor multiplies every spring and anchor, which kappa does); nullopt when there is no
/// finite positive factor.
std::optional<Params> with_kappa_ceiling(const Params& current, const KnobsResult& r);
/// `current` with rayleigh_mass = alpha and rayleigh_stiffness = beta of the pair; nullopt when
/// there is no pair or it is not non-negative.
std::optional<Params> with_rayleigh_pair(const Params& current, const KnobsResult& r);

}  // namespace dampbound::ui
