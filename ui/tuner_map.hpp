#pragma once
// The tuner's stability map (GL-free): the outcome of the scene's protocol over a 2-D log
// window around the current parameters (ui/map_grid.hpp), computed on a worker thread, coarse
// to fine, with the boundary lines of ui/map_bounds.hpp. This file schedules the passes and
// restarts; the window's Map tab draws the result with ui/map_plot.hpp like `dampbound map`
// (tests/ui/tuner_map_test.cpp).
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/sweep/map.hpp"
#include "ui/map_bounds.hpp"
#include "ui/map_grid.hpp"

namespace dampbound::ui {

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
  /// Each cell ran step() through Session (dashpot or Rayleigh damping, SPEC 10, which the
  /// batched kernel does not apply), not the batched kernel.
  bool plain = false;
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
  /// the scene does. The scene is shared with the worker, which takes its own copy (a big
  /// mesh's copy is no frame's work).
  void follow(std::shared_ptr<const SceneSpec> scene, std::uint64_t scene_key, const Params& params,
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
  /// The Cancel button: the running computation ends after its current trial and the last
  /// finished pass stays on show; a change that would restart it (follow()) starts it again.
  void cancel() { retire_job(); }

 private:
  /// One computation. A restart cancels the running job and lets it finish on its own: the
  /// frame never waits for it (follow() joins jobs that are done).
  struct Job {
    std::atomic<bool> cancel{false};
    std::atomic<bool> done{false};
    std::thread thread;
  };
  void start(std::shared_ptr<const SceneSpec> scene, const Params& centre, const StopRules& rules,
             const MapView& view);
  /// Cancels the running job, if any (it ends after its current step and publishes nothing
  /// more), and keeps it to be joined by reap().
  void retire_job();
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
