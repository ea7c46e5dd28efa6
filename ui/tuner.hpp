#pragma once
// The interactive tuner's state, free of GL and of any ImGui context: a core Session (the one
// step()), playback, parameter edits that take effect at the next step, pinned runs, and the
// actions of the mesh view (watch, displace, cut). The window's panels only call these;
// tests/ui/tuner_test.cpp drives them without a window.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/io/format.hpp"
#include "dampbound/run/session.hpp"
#include "ui/plot_spec.hpp"
#include "ui/tuner_criteria.hpp"
#include "ui/tuner_trace.hpp"

namespace dampbound::ui {

/// A pinned run: a copy of a run's trace and what produced it, overlaid on the plots.
struct Pin {
  std::string name;   ///< legend and CSV label (editable)
  std::string scene;  ///< the scene's name
  Params params;
  StopRules rules;
  RunResult result;
  int watched = 0;
  std::vector<StepSample> trace;    ///< every step (exported to CSV)
  std::vector<StepSample> reduced;  ///< decimated once for plotting
  ImU32 color = 0;
  bool visible = true;
  /// True when the run went from the scene's start with these parameters and nothing done by
  /// hand (no drag, cut, perturbation or mid-run change): a headless replay gives `result`.
  bool replayable = true;
};

/// How playback advances the session.
struct PlaybackOptions {
  int steps_per_frame = 10;       ///< steps per drawn frame while playing (1..10000)
  bool pause_at_verdict = false;  ///< pause when the verdict is final: at the iteration limit
                                  ///< (settled or not, SPEC 8) or at a divergence
  size_t max_trace = 1000000;     ///< pause when the trace holds this many steps (~100 MB)
  /// A frame steps at most this long (seconds), fewer than steps_per_frame if need be, so a
  /// large mesh or a large steps_per_frame never freezes the window; at least one step.
  double frame_budget_seconds = 0.05;
};

/// The scene with the settled rule (SPEC 8): the tuner answers "does it stay stable?".
SceneSpec with_settled_rule(SceneSpec scene);

/// The default name of a pin: "gamma G, m M, kappa K, dt D, POLICY" (with the factor for
/// the upper policy).
std::string params_label(const Params& params);

/// Short number for the panels: %.4g, and "inf", "-inf" or "-" (NaN) when not finite, so the
/// window never shows NaN.
inline std::string fmt(double x) { return format_digits(x, 4, "-"); }

/// The paper's lower bound (eq. 5, SPEC 3: kappa_i the stiffest spring or anchor at node i)
/// against the user's gamma_i at every free node of a model (its current parameters).
struct LowerBoundCheck {
  int nodes = 0;        ///< free nodes with gamma_lo_i > 0
  int below = 0;        ///< of them, with gamma_i < gamma_lo_i (underdamped)
  int worst = -1;       ///< the node with the smallest gamma_i / gamma_lo_i (-1: none)
  double ratio = 1;     ///< that smallest ratio (1: exactly at its bound)
  double lower = 0;     ///< its gamma_lo_i (mass unit/s)
  bool uniform = true;  ///< every node has the same ratio (one bound speaks for all)
};
LowerBoundCheck check_lower_bound(const Model& model);

/// The nodal damping ratio of a model's free nodes in words: "0.5" when every node has the
/// same zeta_i = gamma_i / 2 sqrt(m_i kappa_i), else "0.25 .. 1.2 over the nodes" ("-": none).
std::string zeta_text(const Model& model);

/// Buckets of the plot decimation (ui/tuner_trace.hpp): up to twice as many samples.
constexpr size_t kPlotBuckets = 512;

class Tuner {
 public:
  /// Starts with the scene's own parameters and stop rules under the settled rule, paused.
  explicit Tuner(SceneSpec scene);

  /// Loads a scene file (core load_scene) and switches to it with its own parameters. On
  /// failure the current scene stays and *error holds the one-line reason.
  bool open_scene(const std::string& path, std::string* error);
  /// Switches to `scene` with its own parameters; pins are kept.
  void set_scene(SceneSpec scene);

  /// The session: model, state, trace and verdict (read only; change it through the tuner).
  const Session& session() const { return *session_; }
  const SceneSpec& scene() const { return session_->scene(); }
  const Params& params() const { return session_->params(); }

  /// New parameters, effective at the next step (state, trace and cuts are kept). Invalid
  /// parameters are refused with *error set and nothing changed.
  bool set_params(const Params& params, std::string* error = nullptr);
  /// The damping given as a ratio (SPEC 10) instead of gamma: the parameters panel's
  /// gamma|zeta toggle. In zeta mode each node's gamma_i = zeta * 2 sqrt(m_i kappa_i) *
  /// gamma_scale_i (core resolve_zeta(), as `--zeta` and a scene's `zeta` give it), and a
  /// change of m or kappa keeps zeta (gamma follows); a gamma set through set_params() (Suggest's
  /// apply buttons) moves zeta with it. Turning it on for a scene whose nodes' lower bounds
  /// differ from 2 sqrt(m kappa) (regions, meshes) resolves the scene's damping scales once: the
  /// run restarts from the scene's start with the current parameters (the notice says so).
  bool zeta_mode() const { return zeta_mode_; }
  void set_zeta_mode(bool on);
  /// zeta = gamma / 2 sqrt(m kappa): every node's ratio over its gamma_scale_i once the scene
  /// is resolved (zeta_resolved()); in gamma mode, the reference node's ratio.
  double zeta() const;
  /// True when gamma = zeta * 2 sqrt(m kappa) gives every free node zeta_i = zeta *
  /// gamma_scale_i: a scene given with zeta, one whose nodes all have the plain lower bound,
  /// or one zeta mode has resolved.
  bool zeta_resolved() const { return zeta_resolved_; }
  /// Sets zeta (zeta mode on): gamma = zeta * 2 sqrt(m kappa), effective at the next step.
  bool set_zeta(double zeta, std::string* error = nullptr);
  /// Iteration limit of the protocol (where the settled rule decides), >= 1.
  void set_max_iterations(int n);

  /// True while advance() steps.
  bool playing() const { return playing_; }
  /// Play or pause; refusing to play (returns false) when the run cannot step.
  bool set_playing(bool play);
  /// Steps per frame, pause at the verdict, trace cap.
  PlaybackOptions& playback() { return playback_; }
  const PlaybackOptions& playback() const { return playback_; }

  /// One drawn frame: steps_per_frame steps when playing (fewer where they would take longer
  /// than frame_budget_seconds), none when paused. Returns the number of steps taken. Playback stops when the run diverges (it cannot go on), when the
  /// trace is full, and at the verdict when pause_at_verdict is set.
  int advance();
  /// The last advance() that the frame budget cut short: the steps it took and the
  /// steps_per_frame asked (the status says so while it binds); {0, 0} when the last one
  /// took every step asked (or playback stopped it at a verdict).
  struct BudgetCut {
    int taken = 0, asked = 0;
  };
  BudgetCut budget_cut() const { return budget_cut_; }
  /// Up to n steps now, playing or not (single step). Returns the steps taken.
  int step(int n = 1) { return step(n, -1); }
  /// As step(n), stopping after budget_seconds (at least one step; a negative budget: none).
  int step(int n, double budget_seconds);
  /// From any thread: no further step in this or any later call (the window is closing).
  void stop_stepping() { stop_.store(true, std::memory_order_relaxed); }
  /// False after divergence (reset to go on) or with a full trace.
  bool can_step() const;

  /// Back to the scene's perturbed state and topology with the current parameters.
  void reset();
  /// Applies the scene's perturbation again on top of the current state.
  void perturb();
  /// The mesh view's drag: moves one node by `offset` (cm).
  void displace(int node, const Vec3& offset);
  /// max_i |x_i - X_i| (cm) of the state as it is now (the trace's last step says it after a
  /// step; this also holds at the perturbed start and after a drag); inf if not finite.
  double max_displacement_now() const;
  /// |x_c - X_c| (cm) of the watched node now.
  double watched_displacement_now() const;
  /// Watches another node (its bounds and displacement go into the trace from now on).
  void watch(int node);
  /// Removes the springs (the cut tool); the bounds react at the next step. Returns how many.
  int cut(const std::vector<int>& springs);

  /// True while the current run is what a headless replay of the scene with the current
  /// parameters gives: since the last reset nothing was dragged, cut or perturbed by hand and
  /// no parameter or the iteration limit changed after the first step.
  bool replayable() const { return replayable_; }

  /// Pins the current run under `name` (params_label() when empty); returns the pin.
  Pin& pin(const std::string& name = "");
  /// Removes a pin (an index out of range is ignored).
  void unpin(size_t index);
  /// The pins, oldest first (names and visibility are editable).
  std::vector<Pin>& pins() { return pins_; }
  const std::vector<Pin>& pins() const { return pins_; }
  /// Colour of the current run on the plots.
  ImU32 current_color() const;

  /// The current trace decimated for plotting (updated incrementally).
  const std::vector<StepSample>& reduced_trace();
  /// Changes whenever another scene is loaded.
  std::uint64_t scene_version() const { return scene_version_; }
  /// Changes whenever the trace starts over (reset, new scene).
  std::uint64_t generation() const { return generation_; }
  /// Changes whenever the springs change (cut, reset, new scene): the renderer's cue.
  std::uint64_t topology() const { return topology_; }
  /// Changes whenever positions or node states may have changed (a step, a drag, a
  /// perturbation, a cut, a reset): the mesh view redraws only then (or when the camera moves).
  std::uint64_t state_version() const { return state_version_; }

  /// The last thing worth telling the user (e.g. "diverged at 45: reset to go on").
  const std::string& notice() const { return notice_; }
  /// Replaces the notice (the window shows warnings there).
  void set_notice(std::string text) { notice_ = std::move(text); }
  /// Steps taken since construction and the wall time they took (for steps per second).
  long long total_steps() const { return total_steps_; }
  double step_seconds() const { return step_seconds_; }

  /// The exact upper limit of gamma for the chosen integrator (SPEC 7,
  /// core/analysis/linear_stability_exact.hpp), at rest or at the current state (TunerCriteria),
  /// recomputed when the parameters or the springs change (or the state, when it follows
  /// it); nullopt when it is infinite or cannot be computed.
  std::optional<double> exact_gamma_max() {
    return criteria_.exact_gamma_max(*session_, topology_, state_version_);
  }
  /// Every stability criterion at the current state, updated on each call.
  const std::vector<CriterionResult>& criteria() {
    return criteria_.evaluate(*session_, topology_, state_version_);
  }
  /// The exact analysis as the criteria use it (null when unavailable).
  const ExactStability* exact() { return criteria_.exact(*session_, topology_, state_version_); }
  /// The criteria cache (the exact analysis; tests read its counters).
  TunerCriteria& criteria_state() { return criteria_; }

 private:
  void on_new_trace();
  /// Makes a new session for `scene` (tuned: zeta resolved, the settled rule).
  void new_session(SceneSpec scene);

  std::unique_ptr<Session> session_;
  PlaybackOptions playback_;
  bool playing_ = false;
  std::atomic<bool> stop_{false};  ///< stop_stepping() was called
  std::vector<Pin> pins_;
  int next_color_ = 1;
  /// At most ~1000 samples per plotted trace: about one per pixel column of a plot, which
  /// keeps the triangles a software rasteriser must set up in check on long runs.
  TraceDecimator decimator_{kPlotBuckets};
  std::uint64_t generation_ = 1;
  std::uint64_t scene_version_ = 1;
  std::uint64_t topology_ = 1;
  std::uint64_t state_version_ = 1;
  std::string notice_;
  bool replayable_ = true;
  BudgetCut budget_cut_;
  long long total_steps_ = 0;
  double step_seconds_ = 0;
  TunerCriteria criteria_;
  bool zeta_mode_ = false;
  bool zeta_resolved_ = false;
};

}  // namespace dampbound::ui
