#pragma once
// The tuner's stability map (GL-free): the outcome of the scene's protocol over a 2-D log
// window around the current parameters, any two of m, kappa, gamma, dt, computed with the
// batched sweep kernel (core/sweep/kernel.hpp) on a worker thread, coarse to fine, with the
// paper's lower bound (eq. 5) and the exact linear limit (SPEC 7) as lines. The window's Map
// tab draws it with ui/map_plot.hpp like `dampbound map`; tests/ui/tuner_map_test.cpp
// compares its cells with `sweep`.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/sweep/safe_edge.hpp"
#include "core/sweep/kernel.hpp"
#include "core/sweep/map.hpp"

namespace dampbound::ui {

/// A parameter a map axis can vary.
enum class MapParam { m = 0, kappa = 1, gamma = 2, dt = 3 };

/// "m", "kappa", "gamma" or "dt".
const char* to_string(MapParam p);
/// The axis label with its unit, e.g. "gamma (mass unit/s)".
std::string map_axis_label(MapParam p);
/// The value of `p` in `params`, and `params` with it set.
double get_param(const Params& params, MapParam p);
void set_param(Params& params, MapParam p, double value);

/// What the map shows: two axes, and how far the window reaches around the current point.
struct MapView {
  MapParam x = MapParam::dt;      ///< horizontal axis
  MapParam y = MapParam::gamma;   ///< vertical axis
  double decades = 1.0;           ///< the window spans centre / 10^decades .. centre * 10^decades
  int finest = 32;                ///< cells per axis of the last (finest) pass
};

/// n cells on a log axis over [centre / 10^decades, centre * 10^decades]: n + 1 edges.
std::vector<double> map_log_edges(double centre, double decades, int n);
/// The geometric centre of each cell (sqrt of its edges' product): the value a cell's trial
/// runs with.
std::vector<double> map_cell_centres(const std::vector<double>& edges);

/// The trials of a grid: `base` with the x axis set to xs[ix] and the y axis to ys[iy]; row
/// major with rows along y (cell = iy * xs.size() + ix), as MapPanel cells.
std::vector<TrialParams> map_trials(const Params& base, MapParam x, const std::vector<double>& xs,
                                    MapParam y, const std::vector<double>& ys);

/// Runs `trials` of `scene` (policy, integrator from `base`) with the batched kernel on the
/// calling thread. Empty when `cancel` became true. Throws std::invalid_argument when the
/// kernel cannot run the scene (batch_kernel_unsupported).
std::vector<TrialResult> run_map_trials(const SceneSpec& scene, const Params& base,
                                        const StopRules& rules,
                                        const std::vector<TrialParams>& trials,
                                        const std::atomic<bool>* cancel = nullptr);

/// The boundary lines of the window: the paper's lower bound gamma = 2 C sqrt(m kappa) with
/// C the worst node's sqrt(mass_scale * kappa_scale) / gamma_scale (eq. 5, SPEC 3), and, when
/// every free node has the same gamma_scale / mass_scale = r, the exact linear limit of the
/// paper's step lambda_unit kappa dt^2 + 2 r gamma dt = 4 m (SPEC 7; lambda_unit from
/// unit_stiffness_eigenvalue). Each is solved for one axis along the other, sampled on
/// `samples` log points.
struct MapBoundConstants {
  double lower = 0;          ///< C above (NaN: no node has a lower bound)
  double lambda_unit = 0;    ///< lambda_max at m = kappa = 1 (1/s^2); NaN: no exact line
  double rate_ratio = 1;     ///< r above; NaN when it differs between nodes
  SafeUnit safe;             ///< SPEC 9's row sums at rest (the safe bound's line; any scene)
};
MapBoundConstants map_bound_constants(const SceneSpec& scene);
std::vector<MapLine> map_bound_lines(const MapBoundConstants& k, const Params& base,
                                     const MapView& view, const std::vector<double>& x_edges,
                                     const std::vector<double>& y_edges, int samples = 200);

/// One finished pass of the map.
struct MapResult {
  MapView view;
  Params base;                 ///< the parameters the window is centred on
  int max_iterations = 0;
  StopRule rule = StopRule::first_entry;  ///< the verdict rule of the cells (SPEC 8)
  std::vector<double> x_edges, y_edges;
  std::vector<TrialResult> cells;  ///< row major, rows along y
  std::vector<MapLine> lines;
  int pass = 0;                ///< 1 = coarsest
  bool finest = false;         ///< the last pass of this window
  double seconds = 0;          ///< wall time of this pass
};

/// The map as a core MapPanel (what ui/map_plot.hpp draws): each cell its trial's outcome,
/// restored cells with their iteration.
MapPanel map_result_panel(const MapResult& result);

/// The worker: follow() starts (or restarts) the computation when the scene, the parameters
/// other than the axes, the rules or the view change, or when the current point leaves the
/// middle half of the window; passes of 8, 16, 32 ... up to view.finest cells per axis.
class TunerMap {
 public:
  TunerMap() = default;
  ~TunerMap();
  TunerMap(const TunerMap&) = delete;
  TunerMap& operator=(const TunerMap&) = delete;

  /// Call every frame the map is shown (cheap when nothing changed). `scene_key` changes when
  /// the scene does.
  void follow(const SceneSpec& scene, std::uint64_t scene_key, const Params& params,
              const StopRules& rules, const MapView& view);
  /// The latest finished pass (null before the first).
  std::shared_ptr<const MapResult> result() const;
  /// True while the worker computes.
  bool busy() const { return job_ && !job_->done.load(); }
  /// Why the map cannot be computed for this scene ("" when it can): what
  /// batch_kernel_unsupported says, or the worker's error.
  std::string unsupported() const;
  /// How many times the computation was (re)started (tests).
  int starts() const { return starts_; }
  /// Waits until the worker has finished every pass (tests and scripted runs).
  void wait();
  /// Stops every worker and waits for them (each returns after its current step).
  void stop();

 private:
  /// One computation. A restart cancels the running job and lets it finish on its own: the
  /// frame never waits for it (follow() joins jobs that are done).
  struct Job {
    std::atomic<bool> cancel{false};
    std::atomic<bool> done{false};
    std::thread thread;
  };
  void start(const SceneSpec& scene, const Params& centre, const StopRules& rules,
             const MapView& view);
  void reap(bool all);

  std::shared_ptr<Job> job_;
  std::vector<std::shared_ptr<Job>> retired_;
  mutable std::mutex mutex_;  ///< guards result_, unsupported_, bounds_
  std::shared_ptr<const MapResult> result_;
  std::string unsupported_;
  std::shared_ptr<const MapBoundConstants> bounds_;  ///< of scene_key_ (a Lanczos run: once)
  std::uint64_t scene_key_ = 0;
  Params centre_;  ///< the window's centre (the parameters when it started)
  StopRules rules_;
  MapView view_;
  bool started_ = false;
  int starts_ = 0;
};

}  // namespace dampbound::ui
