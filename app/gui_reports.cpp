// What a scripted `dampbound gui --frames N` run says: the Suggest tab's lines on stderr, the
// map it waits for, and the --stats JSON line on stdout (app/gui_reports.hpp). Compiled with the
// window host only (app/CMakeLists.txt).
#include "app/gui_reports.hpp"

#if defined(DAMPBOUND_HAVE_GLFW)
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "app/wait_note.hpp"
#include "core/io/format.hpp"
#include "core/io/report.hpp"

namespace dampbound::app {

/// The Suggest tab's substeps, in one line on stderr (scripted --tab suggest runs).
void print_substeps_line(const ui::BackgroundJob<ui::SubstepsResult>& job) {
  if (job.busy()) {
    std::fprintf(stderr, "gui: substeps did not finish by the last frame\n");
  } else if (!job.error().empty()) {
    std::fprintf(stderr, "gui: substeps failed: %s\n", job.error().c_str());
  } else if (job.result()) {
    const SubstepSuggestion& s = job.result()->substeps;
    const auto count = [](const SubstepCount& c) {
      return c.n == 0 ? std::string("none")
                      : substeps_text(c.n) + " (" +
                            (c.ran ? verdict_short(c.run.result) : std::string("not run")) + ")";
    };
    std::string line = "exact limit " + count(s.exact) + ", safe bound " + count(s.safe);
    if (s.by_running.n > 0) line += ", by running " + count(s.by_running);
    const SubstepCount* use = s.answer();
    line += use ? "; use " + std::to_string(use->n) : std::string("; none verified");
    std::fprintf(stderr, "gui: substeps at frame %s s: %s\n", format_digits(s.frame_dt, 6).c_str(),
                 line.c_str());
  }
}

/// The Suggest tab's stiffness ceiling and Rayleigh pair, in one line each on stderr.
void print_knobs_line(const ui::BackgroundJob<ui::KnobsResult>& job) {
  if (job.busy() || !job.result()) {
    std::fprintf(stderr, "gui: ceiling and pair: %s\n",
                 job.busy() ? "did not finish by the last frame"
                 : job.error().empty() ? "none"
                                       : ("failed: " + job.error()).c_str());
    return;
  }
  const ui::KnobsResult& r = *job.result();
  if (!r.ceiling_error.empty())
    std::fprintf(stderr, "gui: stiffness ceiling: %s\n", r.ceiling_error.c_str());
  else
    std::fprintf(stderr, "gui: stiffness ceiling: factor %s (kappa %s); apply kappa = %s\n",
                 format_digits(r.ceiling.factor, 6).c_str(),
                 format_digits(r.ceiling.factor * r.params.kappa, 6).c_str(),
                 format_digits(ui::kCeilingMargin * r.ceiling.factor * r.params.kappa, 6).c_str());
  if (!r.rayleigh)
    std::fprintf(stderr, "gui: Rayleigh pair: %s\n", r.rayleigh_error.c_str());
  else
    std::fprintf(stderr, "gui: Rayleigh pair for zeta %s: alpha %s 1/s, beta %s s, %s\n",
                 format_digits(r.zeta, 4).c_str(), format_digits(r.rayleigh->alpha, 6).c_str(),
                 format_digits(r.rayleigh->beta, 6).c_str(),
                 r.rayleigh->stable ? "stable at dt" : "NOT stable at dt");
}

/// The scripted last frame of `--tab map`: waits for every pass of the map, saying on stderr
/// which pass is done and how many cells the next one has once the wait passes 2 s.
void wait_for_map(ui::TunerMap& map) {
  WaitNote note("gui");
  while (map.busy()) {
    const auto r = map.result();
    const size_t cells = r ? r->cells.size() : 0;
    note.stage(r ? "stability map: pass " + std::to_string(r->pass) + " done (" +
                       plural(static_cast<long long>(cells), "cell") + " in " +
                       format_human(r->seconds) + " s), the next finer pass running"
                 : std::string("stability map: its first, coarsest pass"));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  map.wait();
}

namespace {

/// Frame-time percentiles after the first frame (startup), in milliseconds (ui/frame_times.hpp).
std::string frame_time_json(const ui::WindowRun& run) {
  const ui::FrameTimeSummary f = ui::summarize_frame_times(run.frame_ms, 1);
  return "\"frame_ms_after_first\":{\"frames\":" + std::to_string(f.frames) +
         ",\"mean\":" + json_number(f.mean) + ",\"p50\":" + json_number(f.p50) +
         ",\"p99\":" + json_number(f.p99) + ",\"max\":" + json_number(f.max) +
         "},\"first_frame_ms\":" + json_number(run.frame_ms.empty() ? 0.0 : run.frame_ms[0]);
}

/// The method of the exact analysis on show at exit (a JSON string), or null when none is.
std::string exact_method_json(ui::GuiApp& app) {
  const ExactStability* e = app.tuner().criteria_state().shown();
  return e ? json_string(to_string(e->method)) : "null";
}

/// Where that analysis was linearised ("rest", "state", "equilibrium"), or null.
std::string exact_at_json(ui::GuiApp& app) {
  const ui::TunerCriteria& c = app.tuner().criteria_state();
  return c.shown() ? json_string(ui::to_string(c.exact_linearised_at())) : "null";
}

}  // namespace

void print_stats(ui::GuiApp& app, const ui::WindowRun& run,
                 const std::string& renderer, int width, int height) {
  app.tuner().criteria_state().wait();  // an analysis still on the worker thread: its result
  const Session& s = app.tuner().session();
  std::printf(
      "{\"frames\":%d,\"iterations\":%d,\"outcome\":\"%s\",\"outcome_iteration\":%d,"
      "\"steps_per_frame\":%d,\"mean_frame_ms\":%s,\"fps\":%s,\"steps_per_second\":%s,"
      "\"step_ms_per_frame\":%s,\"width\":%d,\"height\":%d,\"scene\":%s,\"gamma\":%s,"
      "\"policy\":\"%s\",\"pins\":%zu,\"renderer\":%s,\"exact_method\":%s,\"exact_at\":%s,%s}\n",
      run.frames, s.state().iteration, to_string(s.result().outcome), s.result().iterations,
      app.tuner().playback().steps_per_frame, json_number(run.mean_frame_ms).c_str(),
      json_number(run.mean_frame_ms > 0 ? 1000.0 / run.mean_frame_ms : 0.0).c_str(),
      json_number(app.measured_steps_per_second()).c_str(),
      json_number(run.frames > 0 ? app.tuner().step_seconds() * 1e3 / run.frames : 0.0).c_str(),
      width, height, json_string(s.scene().name).c_str(), json_number(s.params().gamma).c_str(),
      to_string(s.params().policy), app.tuner().pins().size(), json_string(renderer).c_str(),
      exact_method_json(app).c_str(), exact_at_json(app).c_str(), frame_time_json(run).c_str());
}

}  // namespace dampbound::app
#endif
