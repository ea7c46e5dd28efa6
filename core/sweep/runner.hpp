#pragma once
// A whole sweep: grid -> similarity classes -> this shard's classes -> (resume: minus those in
// the journal) -> threads of batched kernels -> journal -> CSV written atomically.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/sweep/csv.hpp"
#include "core/sweep/device.hpp"
#include "core/sweep/grid.hpp"
#include "core/sweep/setup.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// Where a running sweep stands (for the progress display).
struct SweepProgress {
  std::uint64_t trials_total = 0;     ///< trials of this shard
  std::uint64_t trials_done = 0;      ///< trials whose class has finished (resumed included)
  std::uint64_t classes_total = 0;    ///< classes of this shard
  std::uint64_t classes_done = 0;     ///< resumed included
  std::uint64_t classes_resumed = 0;  ///< found in the journal at the start
  std::uint64_t trials_resumed = 0;   ///< trials of those classes
  double elapsed_s = 0;               ///< wall time of this run
  bool final = false;
};

struct SweepRequest {
  SceneSpec scene;
  std::string scene_text;  ///< the scene file's bytes (part of the sweep's identity)
  SweepSpec spec;
  std::string output;  ///< the CSV; the journal is OUTPUT.journal
  bool resume = false;
  int shard = 1, shards = 1;
  int threads = 0;               ///< 0: one per hardware thread
  bool use_kernel = true;        ///< false: every trial through Session (the plain step())
  /// Runs the trials instead of the CPU's threads when set (the GPU sweep); `threads` and
  /// `use_kernel` then do not apply.
  TrialDevice* device = nullptr;
  double sync_interval_s = 1.0;  ///< how often finished classes are fsynced to the journal
  std::function<void(const SweepProgress&)> progress;  ///< ~5 times a second and at the end
  const std::atomic<bool>* cancel = nullptr;           ///< set by a signal handler
};

struct SweepReport {
  SweepHeader header;
  std::uint64_t trials = 0;           ///< trials of this shard (rows written)
  std::uint64_t classes = 0;          ///< classes of this shard
  std::uint64_t classes_run = 0;      ///< stepped in this run
  std::uint64_t classes_resumed = 0;  ///< taken from the journal
  std::uint64_t lane_steps = 0;       ///< trial-steps taken in this run
  long long spring_evaluations_per_step = 0;
  std::uint64_t outcome_trials[6] = {0, 0, 0, 0, 0, 0};  ///< per Outcome, over this shard's trials
  std::uint64_t trials_resumed = 0;   ///< trials whose class came from the journal
  double seconds = 0;                 ///< wall time of this run
  double cpu_seconds = 0;             ///< CPU time of this process (all threads)
  int earlier_runs = 0;               ///< earlier runs that recorded their time in the journal
  double earlier_seconds = 0, earlier_cpu_seconds = 0;  ///< their wall and CPU time in all
  std::uint64_t untimed_classes = 0;  ///< journal classes from runs that recorded no time
  bool cancelled = false;         ///< interrupted: the journal holds what was done
  bool already_complete = false;  ///< --resume found the finished CSV and nothing to do
  bool batched = true;            ///< the batched kernel ran (else Session per trial)
  std::string plain_reason;       ///< why not, when not
  std::string device;             ///< the TrialDevice's name when one ran the trials
  std::vector<SweepRow> rows;     ///< this shard's rows (for the summary and the map)
};

/// CPU time of this process so far, all threads (seconds).
double process_cpu_seconds();

/// Runs (or resumes) the sweep. Throws InputError for a journal of another sweep, or an
/// existing journal without `resume`.
SweepReport run_sweep(const SweepRequest& request);

}  // namespace dampbound
