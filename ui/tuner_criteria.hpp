#pragma once
// The tuner's stability criteria without GL: every criterion of core/analysis/criteria.hpp
// for the current run, updated live, and the suggestions of core/analysis/suggest.hpp computed in the
// background so the window never stalls. tests/ui/tuner_criteria_test.cpp drives it.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <future>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/criteria.hpp"
#include "core/analysis/equilibrium.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/shared_analysis.hpp"
#include "core/analysis/suggest.hpp"
#include "dampbound/run/session.hpp"
#include "ui/background_job.hpp"

namespace dampbound::ui {

/// Where the exact analysis linearises the forces (SPEC 7).
enum class Linearisation {
  rest,         ///< x = X (`dampbound bounds SCENE`)
  state,        ///< the run's current positions (`bounds SCENE --after N`)
  equilibrium,  ///< the static equilibrium under the scene's loads (`bounds --equilibrium`)
};
/// "rest", "state" or "equilibrium" (`gui --linearise`, the --stats line).
const char* to_string(Linearisation at);
/// The inverse of to_string; nullopt for any other text.
std::optional<Linearisation> parse_linearisation(const std::string& text);

/// Why the tuner does not compute the exact analysis for these parameters ("" when it does):
/// dashpot or Rayleigh damping (SPEC 10) with another integrator than the paper's step, or on
/// more free nodes than kGeneralLimitsNodes.
std::string exact_not_computed_reason(const Model& model, const Params& params);
/// The most free nodes for which the tuner computes the general damping matrix's limits (on
/// the worker thread, with progress and Cancel: tissue-block-rayleigh's 5670 free nodes take
/// 2.4 s of CPU, `bounds` 4.4 s wall on 2 busy cores).
inline constexpr int kGeneralLimitsNodes = 50000;
/// The most an interactive frame waits for the Criteria tab's analysis (s).
inline constexpr double kCriteriaFrameWait = 0.05;

/// The criteria of a session. The exact linear analysis (SPEC 7) is linearised at the rest
/// state by default (as `dampbound bounds SCENE` does) and cached until the parameters or the
/// springs change, computed on a worker thread (on a small mesh the frame waits for it up to
/// set_frame_wait; otherwise the last result stays on show meanwhile). At the static equilibrium it is cached the same way, always on the worker
/// thread (Newton's method first). At the current positions it follows the run: recomputed on a
/// worker thread at most every follow_interval (0.2 s) or four analysis durations, whichever is
/// longer, the last result staying on show meanwhile (no frame waits for it). The paper's criteria
/// (eqs. 5, 6 and the sec. 5 check), the classic ones and SPEC 9's safe rows are evaluated at the
/// current state on every call; above worker_nodes free nodes, while only the state moves, at most
/// every follow_interval (each evaluation is a pass over the springs). When one analysis takes
/// longer than 50 ms (a large mesh), a changed key is recomputed at most every four such durations.
/// `state` is the caller's counter of state changes (Tuner's state_version()).
class TunerCriteria {
 public:
  TunerCriteria() = default;
  ~TunerCriteria();
  TunerCriteria(const TunerCriteria&) = delete;
  TunerCriteria& operator=(const TunerCriteria&) = delete;

  /// All criteria, in the order `bounds` prints them. `topology` changes when springs do.
  const std::vector<CriterionResult>& evaluate(const Session& session, std::uint64_t topology,
                                               std::uint64_t state = 0);
  /// The exact analysis (cached); null when it failed (or the state is not finite).
  const ExactStability* exact(const Session& session, std::uint64_t topology,
                              std::uint64_t state = 0);
  /// The exact upper limit of the user's gamma at this dt, when finite and positive: the line
  /// drawn on the envelope plot.
  std::optional<double> exact_gamma_max(const Session& session, std::uint64_t topology,
                                        std::uint64_t state = 0);
  /// Where to linearise (rest by default). A change is analysed anew at the next call.
  void set_linearisation(Linearisation at);
  Linearisation linearisation() const { return at_; }
  /// Linearise at the current positions (true) or at rest (false).
  void set_at_current_state(bool on) {
    set_linearisation(on ? Linearisation::state : Linearisation::rest);
  }
  bool at_current_state() const { return at_ == Linearisation::state; }
  /// Shortest time between two analyses that follow the state (seconds).
  void set_follow_interval(double seconds) { follow_interval_ = seconds; }
  /// The analysis time above which a changed key is throttled (50 ms; tests that count
  /// analyses set it high, so that a slow build, e.g. under sanitizers, counts the same).
  void set_slow_threshold(double seconds) { slow_threshold_ = seconds; }
  /// The exact analysis on show, without starting one (null: none yet, or it failed).
  const ExactStability* shown() const { return exact_ ? &*exact_ : nullptr; }
  /// Waits for an analysis running on the worker thread and takes its result (tests).
  void wait();
  /// True while an analysis runs on the worker thread (the one on show is the last result).
  bool computing() const { return job_.valid(); }
  /// While computing(): seconds since the running analysis started, and what it does ("the
  /// general damping matrix's limits (SPEC 10) at rest", "Newton's method, then ...").
  double computing_seconds() const;
  const std::string& computing_stage() const { return stage_; }
  /// How long the last finished analysis took (s; 0 before the first): the estimate shown.
  double last_seconds() const { return last_seconds_; }
  /// The Criteria tab's Cancel: the running analysis is dropped (it finishes on its own, never
  /// waited for by a frame) and not started again until the parameters, the springs or where
  /// to linearise change; the last result stays on show. cancelled() says so.
  void cancel();
  bool cancelled() const { return cancelled_; }
  /// Meshes with more free nodes than this count as large: no frame waits for their analysis,
  /// and while only the state moves their rows are refreshed at most every follow_interval
  /// (default 5000).
  void set_worker_nodes(int nodes) { worker_nodes_ = nodes; }
  /// How long the frame that starts the analysis at rest of a small mesh without SPEC 10's
  /// damping waits for it (s; it runs on the worker thread like every other): infinite by
  /// default (tests, scripted runs: the frame shows its own parameters' analysis); the
  /// window sets kCriteriaFrameWait.
  void set_frame_wait(double seconds) { frame_wait_ = seconds; }
  /// The most one sparse factorisation of the exact analysis may cost (flops;
  /// ExactOptions::max_factor_flops, default kDefaultFactorBudget). Over it the exact rows say
  /// what Lanczos alone proves. A change is analysed anew at the next call.
  void set_factor_budget(double flops);
  double factor_budget() const { return factor_budget_; }
  /// Where the analysis on show was linearised.
  Linearisation exact_linearised_at() const { return exact_shown_at_; }
  /// Whether the analysis on show was linearised at rest, else at the static equilibrium
  /// (exact_equilibrium()) or at the state of iteration exact_iteration().
  bool exact_at_rest() const { return exact_shown_at_ == Linearisation::rest; }
  /// With the analysis at the static equilibrium: how Newton's method reached it.
  const Equilibrium* exact_equilibrium() const {
    const bool shown = exact_shown_at_ == Linearisation::equilibrium;
    return shown && equilibrium_ && equilibrium_->converged ? &*equilibrium_ : nullptr;
  }
  /// Why the last analysis asked for at the static equilibrium has none ("" when it has):
  /// Newton's method did not converge or needs a factorisation over the budget.
  const std::string& equilibrium_failure() const { return equilibrium_failure_; }
  /// With the analysis at rest: the net force there (not balanced: the rest state is no
  /// equilibrium, and a run leaves it; `bounds --equilibrium` analyses where it settles).
  const NetForce* rest_net_force() const {
    return exact_at_rest() && rest_net_ ? &*rest_net_ : nullptr;
  }
  int exact_iteration() const { return exact_iteration_; }
  /// The iteration of the state the rows on show were evaluated at: on a large mesh, while
  /// only the state moves, up to a follow interval behind the run.
  int rows_iteration() const { return rows_iteration_; }
  /// How many times the exact analysis ran (tests: the cache works).
  int exact_runs() const { return exact_runs_; }
  /// Analyses that took the spectrum certified by one before (SharedAnalysis): a change of
  /// gamma, dt or the damping certifies the spectrum of A no more.
  int spectra_reused() const { return shared_->hits(); }
  /// Another scene: the rows and the analysis on show are dropped (a running analysis is
  /// retired), so that the next call analyses the new scene and shows nothing of the old one.
  void forget();

 private:
  struct Finished {
    std::optional<ExactStability> exact;
    std::optional<NetForce> rest_net;  ///< at rest: the net force there
    std::optional<Equilibrium> equilibrium;  ///< at the equilibrium: Newton's result (no x)
    std::string equilibrium_failure;         ///< at the equilibrium: why there is none
    int iteration = 0;
    Linearisation at = Linearisation::rest;
    double seconds = 0;
  };
  /// Takes the worker's result when it is ready.
  void collect();
  /// The static equilibrium's positions (empty where there is none: f.equilibrium_failure
  /// says why), Newton's result (without its positions) in f.equilibrium.
  static std::vector<Vec3> equilibrium_positions(const Model& model, double factor_budget,
                                                 Finished& f);

  std::vector<CriterionResult> results_;
  std::optional<ExactStability> exact_;
  std::optional<NetForce> rest_net_;
  std::optional<Equilibrium> equilibrium_;
  std::string equilibrium_failure_;
  std::future<Finished> job_;  ///< the analysis at the current state, when one runs
  /// The analyses' spectrum and pattern analysis, from one to the next (their workers').
  std::shared_ptr<SharedAnalysis> shared_ = std::make_shared<SharedAnalysis>();
  /// Jobs whose result is of no use any more (the analysis moved back into the frame while
  /// they ran): kept until they finish, so that no frame waits for one.
  std::vector<std::future<Finished>> retired_;
  std::uint64_t topology_ = 0, state_ = 0;
  Params key_;
  bool have_key_ = false;
  Linearisation at_ = Linearisation::rest;
  double follow_interval_ = 0.2;
  double slow_threshold_ = 0.05;
  int worker_nodes_ = 5000;
  double frame_wait_ = std::numeric_limits<double>::infinity();
  double factor_budget_ = kDefaultFactorBudget;
  int exact_iteration_ = 0;
  Linearisation exact_shown_at_ = Linearisation::rest;
  int exact_runs_ = 0;
  std::string stage_;       ///< what the running analysis does
  bool cancelled_ = false;  ///< the analysis of key_ was cancelled
  double last_time_ = 0, last_seconds_ = 0;  ///< when the last analysis started, how long it took
  std::uint64_t exact_version_ = 0;  ///< counts the results exact_ has held
  // What results_ were evaluated for, and when.
  bool rows_valid_ = false;
  std::uint64_t rows_topology_ = 0, rows_exact_version_ = 0;
  Params rows_key_;
  double rows_time_ = 0;
  int rows_iteration_ = 0;
};

/// What the Suggest button produced, and for which parameters.
struct Suggestion {
  Params params;              ///< the parameters it was asked for
  DampingSuggestion damping;  ///< damping range and fastest-settling gamma at params.dt
  StepSuggestion step;        ///< largest stable dt at params.gamma
  int springs = 0;            ///< springs of the mesh it was computed for
  int springs_cut = 0;        ///< of which cut away before (by hand or by the scene)
};

/// Runs suggest_damping and suggest_step on a worker thread (each verified through Sessions).
class TunerSuggest {
 public:
  /// Starts a computation for `scene` and these parameters (`cut`: springs the scene has
  /// lost to cuts, for the record); ignored while one is running.
  void start(const SceneSpec& scene, const Params& params, const StopRules& rules, int cut = 0);
  /// The same for the mesh the session has now (Session::current_scene(): the cuts made so
  /// far count) with its parameters and rules. The worker builds that scene from the
  /// session's shared scene and model: no copy of the mesh on the frame.
  void start(const Session& session);
  /// True while a computation runs.
  bool busy() const { return job_.busy(); }
  /// Collects a finished computation (call once per frame); true when a result arrived.
  bool poll() { return job_.poll(); }
  /// Waits for a running computation (tests).
  void wait() { job_.wait(); }
  /// The Cancel button: the running computation's result is dropped and its worker stops
  /// before its next stage (SuggestOptions::progress: the exact analysis, a trial run or a
  /// verifying run); it is joined later, and closing the window does not wait for it.
  void cancel() { job_.cancel(); }
  /// Seconds since the running computation started.
  double seconds() const { return job_.seconds(); }
  /// Where the running computation is: "damping range, stage 2 of 4: verifying the lower
  /// end of the range" (empty before its first stage).
  std::string progress() const { return job_.progress(); }
  /// True when the last computation was cancelled (nothing new to show).
  bool cancelled() const { return job_.cancelled(); }
  /// The last finished suggestion.
  const std::optional<Suggestion>& result() const { return job_.result(); }
  /// One line when the computation threw.
  const std::string& error() const { return job_.error(); }
  /// The factorisation budget of the next computation (SuggestOptions::max_factor_flops,
  /// default kDefaultFactorBudget); over it the suggestions are what is proved stable
  /// without a factorisation (DampingSuggestion::proved_only).
  void set_factor_budget(double flops) { factor_budget_ = flops; }
  /// The worker (the tab's Cancel, progress and error line read it).
  BackgroundJob<Suggestion>& job() { return job_; }
  /// Another scene: nothing of the last one on show (BackgroundJob::clear).
  void clear() { job_.clear(); }

 private:
  void launch(std::shared_ptr<const SceneSpec> scene, std::shared_ptr<const Model> model,
              int iteration, const Params& params, const StopRules& rules, int cut);

  BackgroundJob<Suggestion> job_;
  double factor_budget_ = kDefaultFactorBudget;
};

/// `current` with the fastest-settling gamma of the suggestion (policy unchanged).
Params with_best_gamma(const Params& current, const Suggestion& s);
/// `current` with the recommended dt of the suggestion (every dt criterion accepts it).
Params with_suggested_dt(const Params& current, const Suggestion& s);

}  // namespace dampbound::ui
