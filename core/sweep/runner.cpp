#include "core/sweep/runner.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <memory>
#include <mutex>
#include <random>
#include <thread>

#include "core/io/files.hpp"
#include "core/sweep/journal.hpp"
#include "core/sweep/trials.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string absolute_path(const std::string& path) {
  if (path.empty()) return path;
  char buf[PATH_MAX];
  return ::realpath(path.c_str(), buf) ? std::string(buf) : path;
}

/// The id and shard line of an existing sweep CSV, "" when it is not one.
std::string csv_identity(const std::string& path) {
  std::ifstream in(path);
  std::string line, id, shard;
  for (int k = 0; k < 12 && std::getline(in, line); ++k) {
    if (line.rfind("# sweep-id: ", 0) == 0) id = line.substr(12);
    if (line.rfind("# shard: ", 0) == 0) shard = line.substr(9);
  }
  return id.empty() ? "" : id + " " + shard;
}

/// Steps the classes `todo` on `threads` threads; hands each result to `done` on the
/// calling thread, and calls `tick` about five times a second. Returns the lane-steps.
std::uint64_t run_classes(const SweepRequest& rq, const SweepGrid& grid,
                          const TrialClasses& classes, const std::vector<std::uint32_t>& todo,
                          bool batched, int threads,
                          const std::function<void(std::uint32_t, const TrialResult&)>& done,
                          const std::function<void(bool)>& tick) {
  std::atomic<size_t> next{0};
  std::atomic<int> running{threads};
  std::atomic<std::uint64_t> lane_steps{0};
  std::mutex mu;
  std::condition_variable cv;
  std::vector<std::pair<std::uint32_t, TrialResult>> pending;
  std::exception_ptr error;
  // Set on Ctrl-C (rq.cancel) and when this thread fails (a full disk under the journal): the
  // workers stop at their next step, and are joined before the error goes on.
  std::atomic<bool> halt{false};
  auto cancelled = [&] { return rq.cancel && rq.cancel->load(std::memory_order_relaxed); };
  auto take = [&](std::uint32_t& cls) {
    if (halt.load(std::memory_order_relaxed) || cancelled()) return false;
    const size_t i = next.fetch_add(1);
    if (i >= todo.size()) return false;
    cls = todo[i];
    return true;
  };
  auto give = [&](std::uint32_t cls, const TrialResult& r) {
    std::lock_guard<std::mutex> lock(mu);
    pending.emplace_back(cls, r);
  };
  auto worker = [&] {
    try {
      const TrialSource source = [&](std::size_t& id, TrialParams& p) {
        std::uint32_t cls = 0;
        if (!take(cls)) return false;
        id = cls;
        p = grid.params(classes.representative[cls]);
        return true;
      };
      const TrialSink sink = [&](std::size_t id, const TrialResult& r) {
        give(static_cast<std::uint32_t>(id), r);
      };
      if (rq.device) {
        lane_steps += rq.device->run(source, sink, &halt);
      } else if (batched) {
        BatchKernel kernel(rq.scene, rq.spec.policy, rq.spec.rules);
        lane_steps += kernel.run(source, sink, &halt);
      } else {
        std::uint32_t cls = 0;
        while (take(cls)) {
          const TrialResult r = run_reference(rq.scene, rq.spec.policy, rq.spec.rules,
                                              grid.params(classes.representative[cls]), &halt);
          if (r.outcome == Outcome::running) break;  // halted mid-trial
          lane_steps += static_cast<std::uint64_t>(r.iterations);
          give(cls, r);
        }
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mu);
      if (!error) error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mu);
      --running;
    }
    cv.notify_all();
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  std::vector<std::pair<std::uint32_t, TrialResult>> batch;
  try {
    for (;;) {
      bool finished = false;
      {
        std::unique_lock<std::mutex> lock(mu);
        cv.wait_for(lock, std::chrono::milliseconds(rq.sync_interval_s < 0.2 ? 20 : 200),
                    [&] { return running == 0; });
        finished = running == 0;
        batch.swap(pending);
      }
      if (cancelled()) halt = true;
      for (const auto& [cls, r] : batch) done(cls, r);
      batch.clear();
      tick(finished);
      if (finished) break;
    }
  } catch (...) {
    halt = true;
    for (auto& th : pool) th.join();
    throw;
  }
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
  return lane_steps.load();
}

/// The CSV's metadata: the sweep's identity, definition, size and part.
SweepHeader sweep_header(const SweepRequest& rq, const SweepGrid& grid,
                         const TrialClasses& classes) {
  SweepHeader h;
  h.definition = sweep_definition(rq.spec);
  h.policy = rq.spec.policy;
  h.sweep_id = sweep_id(rq.scene_text, h.definition);
  h.scene_path = absolute_path(rq.scene.path);
  h.scene_name = rq.scene.name;
  h.trials = grid.trials();
  h.classes = classes.count();
  h.similarity = classes.similarity ? "on" : "off (" + classes.reason + ")";
  h.shard = rq.shard;
  h.shards = rq.shards;
  h.rule = rq.spec.rules.rule;
  h.damping = rq.spec.has_damping_axes();
  return h;
}

/// The rows of a finished CSV, read back by a resume that finds nothing to do.
void report_already_complete(const std::string& csv, SweepReport& rep) {
  rep.already_complete = true;
  for (SweepRow& r : read_sweep_csv(csv).rows) {
    ++rep.outcome_trials[static_cast<size_t>(r.outcome)];
    rep.rows.push_back(r);
  }
}

}  // namespace

double process_cpu_seconds() {
  struct rusage ru {};
  ::getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

namespace {

/// The output checks before any work: the sizes, writable CSV and journal paths, and a journal
/// left by an interrupted run only with --resume. Returns whether that journal exists.
bool check_outputs(const SweepRequest& rq, const SweepGrid& grid, const std::string& journal_path) {
  check_sweep_resources(grid, rq.output, rq.shards);
  check_writable(rq.output);
  check_writable(journal_path);  // not a directory or a device
  const bool journal_exists = ::access(journal_path.c_str(), F_OK) == 0;
  if (journal_exists && !rq.resume)
    throw InputError("-o: " + journal_path +
                     " exists: an earlier run of this sweep was interrupted; add --resume to "
                     "finish it, or delete the journal to start over");
  return journal_exists;
}

/// This shard's classes and what is known of them: each class's trial count, its result and
/// whether it is finished, and the progress counters.
struct ShardState {
  const SweepRequest& rq;
  std::vector<std::uint32_t> multiplicity;
  std::vector<TrialResult> results;
  std::vector<std::uint8_t> finished;
  SweepProgress progress;

  ShardState(const SweepRequest& request, const TrialClasses& classes)
      : rq(request),
        multiplicity(classes.count(), 0),
        results(classes.count()),
        finished(classes.count(), 0) {
    for (std::uint32_t c : classes.class_of) ++multiplicity[c];
    for (std::uint32_t c = 0; c < classes.count(); ++c)
      if (in_shard(c)) {
        ++progress.classes_total;
        progress.trials_total += multiplicity[c];
      }
  }

  bool in_shard(std::uint32_t c) const {
    return static_cast<int>(c % static_cast<std::uint32_t>(rq.shards)) == rq.shard - 1;
  }

  void finish(std::uint32_t c, const TrialResult& r) {
    results[c] = r;
    finished[c] = 1;
    progress.trials_done += multiplicity[c];
  }

  /// The classes still to run, in a fixed shuffled order: the cost of a class varies along
  /// the grid, so shuffling keeps the threads balanced and the time-remaining estimate honest.
  std::vector<std::uint32_t> todo() const {
    std::vector<std::uint32_t> out;
    for (std::uint32_t c = 0; c < finished.size(); ++c)
      if (in_shard(c) && !finished[c]) out.push_back(c);
    std::mt19937_64 rng(0x5eedULL);
    for (size_t i = out.size(); i > 1; --i) std::swap(out[i - 1], out[rng() % i]);
    return out;
  }
};

/// Opens the journal: with --resume and a journal on disk, takes its finished classes into
/// `state` and its earlier runs' times into `rep`, and cuts off a damaged tail; else starts a
/// new one. `run` is this run's number in the journal's time records.
std::unique_ptr<Journal> open_journal(const std::string& journal_path, bool journal_exists,
                                      const std::string& journal_header,
                                      std::uint64_t class_count, ShardState& state,
                                      SweepReport& rep, int& run) {
  const SweepRequest& rq = state.rq;
  run = 1;
  if (!(rq.resume && journal_exists))
    return std::make_unique<Journal>(journal_path, journal_header);
  const JournalContents jc = read_journal(journal_path, journal_header, class_count);
  run = jc.runs + 1;
  rep.earlier_runs = jc.runs;
  rep.earlier_seconds = jc.wall_s;
  rep.earlier_cpu_seconds = jc.cpu_s;
  rep.untimed_classes =
      jc.entries.size() > jc.timed_classes ? jc.entries.size() - jc.timed_classes : 0;
  for (const JournalEntry& e : jc.entries) {
    if (!state.in_shard(e.cls))
      throw InputError(journal_path + ": class " + std::to_string(e.cls) + " is not in shard " +
                       std::to_string(rq.shard) + "/" + std::to_string(rq.shards));
    state.finish(e.cls, e.result);
    ++state.progress.classes_resumed;
  }
  // Cuts a damaged tail off (valid_bytes 0: not even the header survived, start afresh).
  return std::make_unique<Journal>(journal_path, journal_header, jc.valid_bytes);
}

/// The threads a sweep uses: --threads, or one per hardware thread, at most one per class.
int sweep_threads(const SweepRequest& rq, size_t classes_to_run) {
  const int threads =
      rq.threads > 0 ? rq.threads : static_cast<int>(std::thread::hardware_concurrency());
  return std::max(1, std::min<int>(threads, static_cast<int>(std::max<size_t>(classes_to_run, 1))));
}

/// The scene's params with each swept SPEC 10 damping at its largest value: non-zero where
/// any trial has that damping (batch_kernel_unsupported() asks no more).
Params damping_extremes(Params p, const SweepSpec& s) {
  for (auto [axis, value] : {std::pair{&s.kd, &p.kd}, {&s.rayleigh_mass, &p.rayleigh_mass},
                             {&s.rayleigh_stiffness, &p.rayleigh_stiffness}})
    if (!axis->values.empty()) {
      *value = 0;
      for (const Decimal& d : axis->values) *value = std::max(*value, d.value());
    }
  return p;
}

}  // namespace

SweepReport run_sweep(const SweepRequest& rq) {
  const Clock::time_point t0 = Clock::now();
  const double cpu0 = process_cpu_seconds();
  SweepGrid grid(rq.spec);
  const std::string journal_path = rq.output + ".journal";
  const bool journal_exists = check_outputs(rq, grid, journal_path);

  const TrialClasses classes =
      find_classes(grid, similarity_unavailable(rq.scene, !rq.spec.kd.values.empty()));
  SweepReport rep;
  rep.header = sweep_header(rq, grid, classes);
  const SweepHeader& h = rep.header;
  rep.plain_reason = rq.use_kernel
                         ? batch_kernel_unsupported(rq.scene, damping_extremes(rq.scene.params, rq.spec))
                               .value_or("")
                         : std::string("--plain");
  if (rq.device) {
    rep.device = rq.device->name();
    rep.plain_reason.clear();
  }
  rep.batched = rep.plain_reason.empty();
  ShardState state(rq, classes);
  SweepProgress& pr = state.progress;
  rep.trials = pr.trials_total;
  rep.classes = pr.classes_total;

  const std::string identity =
      h.sweep_id + " " + std::to_string(rq.shard) + "/" + std::to_string(rq.shards);
  if (rq.resume && !journal_exists && csv_identity(rq.output) == identity) {
    report_already_complete(rq.output, rep);
    rep.seconds = seconds_since(t0);
    return rep;
  }

  const std::string journal_header =
      "dampbound-journal v1 sweep=" + identity + " classes=" + std::to_string(classes.count());
  int run = 1;
  const std::unique_ptr<Journal> journal = open_journal(
      journal_path, journal_exists, journal_header, classes.count(), state, rep, run);
  pr.classes_done = pr.classes_resumed;
  pr.trials_resumed = pr.trials_done;
  rep.classes_resumed = pr.classes_resumed;
  rep.trials_resumed = pr.trials_resumed;
  // Records this run's time so far with each sync: a kill -9 loses no more of it than of
  // the classes.
  const auto record_time = [&] {
    journal->add_time({run, seconds_since(t0), process_cpu_seconds() - cpu0, rep.classes_run});
  };

  const std::vector<std::uint32_t> todo = state.todo();
  Clock::time_point last_sync = Clock::now();
  rep.lane_steps = run_classes(
      rq, grid, classes, todo, rep.batched, rq.device ? 1 : sweep_threads(rq, todo.size()),
      [&](std::uint32_t c, const TrialResult& r) {
        state.finish(c, r);
        journal->add({c, r});
        ++pr.classes_done;
        ++rep.classes_run;
      },
      [&](bool last) {
        if (last || seconds_since(last_sync) >= rq.sync_interval_s) {
          record_time();
          journal->sync();
          last_sync = Clock::now();
        }
        pr.elapsed_s = seconds_since(t0);
        if (rq.progress) rq.progress(pr);
      });
  journal->sync();  // the last tick recorded this run's time
  rep.seconds = seconds_since(t0);
  rep.cpu_seconds = process_cpu_seconds() - cpu0;
  if (pr.classes_done < pr.classes_total) {
    rep.cancelled = true;
    return rep;
  }

  // Every class of the shard is done: the CSV, written whole or not at all.
  rep.spring_evaluations_per_step = rq.scene.model.spring_count() + rq.scene.model.anchor_count();
  write_durably(rq.output, [&](std::FILE* f) {
    write_sweep_header(f, h);
    write_sweep_rows(f, grid, classes, state.results, rq.shard, rq.shards);
  });
  journal->remove();
  rep.rows = sweep_rows(grid, classes, state.results, rq.shard, rq.shards);
  for (const SweepRow& r : rep.rows) ++rep.outcome_trials[static_cast<size_t>(r.outcome)];
  rep.seconds = seconds_since(t0);
  rep.cpu_seconds = process_cpu_seconds() - cpu0;
  pr.elapsed_s = rep.seconds;
  pr.final = true;
  if (rq.progress) rq.progress(pr);
  return rep;
}

}  // namespace dampbound
