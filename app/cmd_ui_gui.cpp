// dampbound gui [SCENE]: the interactive tuner window (Dear ImGui + GLFW + OpenGL 3.3). With
// --frames N it plays N frames and exits (screenshots, frame-time measurement, tests).
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <chrono>
#include <string>
#include <thread>

#include "app/commands.hpp"
#include "app/gui_reports.hpp"
#include "app/options.hpp"
#include "app/wait_note.hpp"
#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "core/io/scene_write.hpp"
#include "core/physics/damping_ratio.hpp"
#include "dampbound/physics/error.hpp"

#if defined(DAMPBOUND_HAVE_GLFW)
#include "ui/close_guard.hpp"
#include "ui/frame_times.hpp"
#include "ui/glfw_host.hpp"
#include "ui/gui_app.hpp"
#include "ui/gui_self_test.hpp"
#include "ui/image.hpp"
#include "ui/tuner_export.hpp"
#endif

namespace dampbound::app::cmd_ui_gui {
namespace {

struct GuiArgs {
  std::string scene, screenshot, size, config_dir;
  int frames = 0, steps_per_frame = 0;
  bool stats = false, play = false, demo = false;
  bool self_test = false;
  bool export_unfinished = false;  ///< --export-unfinished
  std::vector<std::string> self_test_scenes, monkey_scenes = {"paper-plane", "tissue-block"};
  int monkey_events = 1000;
  std::uint64_t monkey_seed = 1;
  std::string tab, linearise;
  std::vector<std::string> pins;  ///< --pin KEY=VALUE[,KEY=VALUE...], repeatable
  std::string save_scene, export_dir, export_prefix = "dampbound";
  double factor_budget = 0;  ///< GFlop (add_factor_budget_option sets the default)
  double frame_dt = 0;       ///< --frame-dt: the Suggest tab's frame time (0: its default)
  int debug_frame_sleep_ms = 0;  ///< hidden --debug-frame-sleep: long frames for input tests
  int expect_iterations = default_expect_tolerance().iterations;
  double expect_displacement = default_expect_tolerance().displacement_factor;
  ParamFlags flags;
};

#if defined(DAMPBOUND_HAVE_GLFW)
/// How long a close (window button, SIGINT, SIGTERM) may take before the watchdog ends the
/// process (the process is gone within 0.3 s of the request: docs/gui.md), and the longest
/// frame of a self-test before it counts as a hang (seconds).
constexpr double kCloseGrace = 0.2;
constexpr double kSelfTestHang = 60.0;

bool have_display() {
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (x != nullptr && *x != '\0') || (w != nullptr && *w != '\0');
}

/// A scene argument as an absolute file name: the file, else a shipped scene of that name.
std::string resolve_scene_path(const std::string& arg) {
  namespace fs = std::filesystem;
  if (fs::exists(arg)) return fs::absolute(arg).string();
  fs::path shipped = fs::path(shipped_scenes_dir()) / arg;
  if (shipped.extension() != ".toml") shipped += ".toml";
  if (fs::exists(shipped)) return shipped.string();
  throw InputError("scene '" + arg + "': no such file, and no shipped scene of that name");
}

/// The widgets the self-test operated and what the monkey did.
void print_self_test(const ui::SelfTest& t, const ui::SelfTestOptions& o) {
  const ui::SelfTestReport& r = t.report();
  std::printf("self-test: %zu widgets operated on %d scenes:\n", r.visited.size(), r.scenes_visited);
  for (const std::string& v : r.visited) std::printf("  %s\n", v.c_str());
  std::printf("self-test: monkey: %d input events (%d per scene on %zu scenes), seed %llu\n",
              r.monkey_events, o.monkey_events, o.monkey_scenes.size(),
              static_cast<unsigned long long>(o.seed));
  std::printf("self-test: OK, %d frames, no abort, no hang\n", r.frames);
}

/// The window's title of a --tab value.
std::string tab_title(const std::string& tab) {
  if (tab == "criteria") return "Criteria";
  if (tab == "pins") return "Pins & export";
  if (tab == "suggest") return "Suggest";
  if (tab == "save") return "Save scene";
  if (tab == "worst") return "Worst nodes";
  if (tab == "map") return "Map";
  if (tab == "mesh") return "Mesh";
  return "Status";
}

#endif

int run(GuiArgs& a) {
#if !defined(DAMPBOUND_HAVE_GLFW)
  (void)a;
  throw std::runtime_error("gui: this dampbound was built without GLFW (DAMPBOUND_GUI=OFF)");
#else
  // Before any thread starts (threads inherit the mask): SIGINT and SIGTERM go to the close
  // guard's watchdog only, which starts the close at once, also while the scene loads.
  ui::block_close_signals();
  ui::CloseGuard guard(kCloseGrace, a.self_test ? kSelfTestHang : 0.0);
  guard.catch_signals();
  // Mesa's shader disk cache runs a thread at nice 19: on a busy machine a thread that low
  // waited up to 2.5 s for the CPU it needs to die, and the process with it (measured on
  // tissue-block while builds ran: exit 1.2 to 2.6 s after the request). Without the cache
  // the first frame takes about 0.2 s longer (docs/gui.md); a user's own setting is kept.
  setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
  if (!a.screenshot.empty() && a.frames <= 0)
    throw InputError("--screenshot needs --frames N (the screenshot is taken after frame N)");
  int width = 0, height = 0;
  if (!a.size.empty()) parse_size(a.size, "--size", width, height);
  if (!a.screenshot.empty()) check_writable(a.screenshot);
  if (!a.save_scene.empty()) {
    try {
      check_writable(a.save_scene);
    } catch (const InputError& e) {
      throw InputError(std::string("--save-scene: ") + e.what());
    }
  }
  if (!a.export_dir.empty() && a.frames <= 0)
    throw InputError("--export needs --frames N (the plots are exported at frame N)");
  if (!a.export_dir.empty()) {
    try {
      ui::export_paths(a.export_dir, a.export_prefix);  // a prefix without a path separator
    } catch (const InputError& e) {
      throw InputError(std::string("--export-prefix: ") + e.what());
    }
  }
  if (a.self_test && a.frames > 0) throw InputError("--self-test runs until it is done: drop --frames");
  ui::SelfTestOptions st;
  std::string self_test_dir;
  if (a.self_test) {
    for (const std::string& s : a.self_test_scenes) st.scenes.push_back(resolve_scene_path(s));
    if (a.self_test_scenes.empty()) {
      for (const auto& e : std::filesystem::directory_iterator(shipped_scenes_dir()))
        if (e.path().extension() == ".toml") st.scenes.push_back(e.path().string());
      std::sort(st.scenes.begin(), st.scenes.end());
    }
    for (const std::string& s : a.monkey_scenes) st.monkey_scenes.push_back(resolve_scene_path(s));
    st.monkey_events = a.monkey_events;
    st.seed = a.monkey_seed;
    // Whatever the widgets write (exports, saved scenes, settings) lands in a folder of its own.
    std::string tmpl = (std::filesystem::temp_directory_path() / "dampbound-self-test-XXXXXX").string();
    if (mkdtemp(tmpl.data()) == nullptr) throw std::runtime_error("gui: cannot make a temporary folder");
    self_test_dir = tmpl;
    if (a.config_dir.empty()) a.config_dir = self_test_dir + "/config";
  }
  ui::GuiOptions o;
  o.config_dir = ui::config_dir(a.config_dir);
  o.scenes_dir = shipped_scenes_dir();
  if (!a.scene.empty()) o.scene = load_scene_arg(a.scene);
  const ParamFlags flags = a.flags;
  if (flags.zeta_opt->count() && !o.scene)
    throw InputError("--zeta: give a SCENE (the ratio is resolved at each of its nodes)");
  if (o.scene) {  // the scene's or --zeta's damping ratio, resolved at each node
    StopRules unused;
    flags.apply(o.scene->params, unused);
    resolve_zeta(o.scene->model, o.scene->params);
  }
  o.overrides = [flags](Params& p, StopRules& r) {
    flags.apply(p, r);
    resolve_zeta(p);  // the scene's spec is resolved above; m and kappa may differ here
  };
  o.steps_per_frame = a.steps_per_frame;
  o.factor_budget = a.factor_budget * 1e9;
  if (!a.linearise.empty()) o.linearise = ui::parse_linearisation(a.linearise);
  o.play = a.play || a.frames > 0;
  o.demo = a.demo;
  o.scripted = a.frames > 0;
  ui::GuiApp app(std::move(o));
  guard.on_signal([&app] { app.tuner().stop_stepping(); });
  struct Unhook {  // the app goes before the guard: the watchdog must not call into it then
    ui::CloseGuard& guard;
    ~Unhook() { guard.on_signal(nullptr); }
  } unhook{guard};
  for (const std::string& text : a.pins)
    ui::pin_run(app.tuner(), ui::parse_pin_request(text, app.tuner().params(),
                                                   app.tuner().session().rules().max_iterations));
  if (flags.zeta_opt->count()) app.tuner().set_zeta_mode(true);  // the slider gives zeta
  if (a.frame_dt > 0) app.set_frame_dt(a.frame_dt);
  app.save_tolerance().iterations = a.expect_iterations;
  app.save_tolerance().displacement_factor = a.expect_displacement;
  if (!have_display())
    throw std::runtime_error(
        "gui: no display (DISPLAY is not set): run it under `xvfb-run -a`, or use `dampbound "
        "figure` for headless plots");
  if (!a.tab.empty()) app.select_tab(tab_title(a.tab));
  if (width == 0) {
    const auto remembered = app.remembered_window_size();
    width = remembered.first > 0 ? remembered.first : 1600;
    height = remembered.second > 0 ? remembered.second : 1000;
  }
  ui::WindowOptions w;
  w.width = width;
  w.height = height;
  w.title = "dampbound - damping bounds tuner";
  w.vsync = a.frames <= 0;  // measured runs draw as fast as they can
  w.max_frames = a.frames;
  w.screenshot_frame = a.screenshot.empty() ? -1 : a.frames - 1;
  std::unique_ptr<ui::SelfTest> self_test;
  if (a.self_test) {
    app.set_export_folder(self_test_dir + "/export");
    self_test = std::make_unique<ui::SelfTest>(app, st);
    std::filesystem::current_path(self_test_dir);
    w.input = [&self_test] { self_test->input(ImGui::GetIO()); };
  }
  app.set_export_unfinished(a.export_unfinished);
  w.on_close_request = [&guard] { guard.request_close(); };
  ui::GlfwHost host(w);
  guard.heartbeat();
  std::string export_message;
  // Scripted (--frames), the Map and Suggest tabs compute as a person would have them: the
  // Map starts when its tab is drawn, Suggest at the first frame as if its button was pressed,
  // and the last frame waits for them (--stats counts the wait).
  const bool map_wait = a.tab == "map" && a.frames > 0;
  const bool suggest_scripted = a.tab == "suggest" && a.frames > 0;
  const ui::WindowRun run = host.run([&](ui::FrameInfo& info) {
    if (ui::CloseGuard::signalled()) {  // closing: no frame's work after the request
      info.close = true;
      return;
    }
    const bool last = info.index == a.frames - 1 && !info.layout_pass;
    if (suggest_scripted && info.index == 0 && !info.layout_pass) {
      app.start_suggest();
      app.start_substeps();
      app.start_knobs();
    }
    if (map_wait && last) wait_for_map(app.map());
    if (suggest_scripted && last)
      app.suggestions().wait(), app.substeps().wait(), app.knobs().wait();
    app.frame(info);
    if (!a.export_dir.empty() && last)
      export_message = app.export_plots(a.export_dir, a.export_prefix);
    if (self_test && self_test->after_frame(info)) info.close = true;
    if (a.debug_frame_sleep_ms > 0 && !info.layout_pass)
      std::this_thread::sleep_for(std::chrono::milliseconds(a.debug_frame_sleep_ms));
    guard.heartbeat(self_test ? self_test->doing() : std::string());
    if (ui::CloseGuard::signalled()) info.close = true;
  });
  // A close request (the window's button, a signal) ends the process now: the settings are
  // saved, and no background work is waited for.
  const bool close_request = ui::CloseGuard::signalled() || (a.frames <= 0 && !a.self_test);
  if (close_request) {
    guard.request_close();
    app.save();
    std::fflush(nullptr);
    std::_Exit(0);
  }
  app.save();
  app.release_gl();
  if (self_test) print_self_test(*self_test, st);
  if (!a.screenshot.empty()) {
    if (!run.screenshot) throw std::runtime_error("gui: the window closed before the screenshot");
    ui::write_png_atomic(*run.screenshot, a.screenshot);
  }
  if (!export_message.empty()) std::fprintf(stderr, "gui: %s\n", export_message.c_str());
  if (suggest_scripted) {  // what the tab shows, in one line
    ui::TunerSuggest& sg = app.suggestions();
    if (sg.busy())
      std::fprintf(stderr, "gui: suggest did not finish by the last frame\n");
    else if (!sg.error().empty())
      std::fprintf(stderr, "gui: suggest failed: %s\n", sg.error().c_str());
    else if (sg.result())
      std::fprintf(stderr, "gui: suggest: gamma in [%s, %s), fastest settling at %s (dt %s)\n",
                   format_digits(sg.result()->damping.gamma_min, 4).c_str(),
                   format_digits(sg.result()->damping.gamma_max, 4).c_str(),
                   format_digits(sg.result()->damping.gamma_best, 4).c_str(),
                   format_digits(sg.result()->params.dt, 4).c_str());
  }
  if (suggest_scripted) print_substeps_line(app.substeps()), print_knobs_line(app.knobs());
  if (!a.save_scene.empty()) {
    std::vector<std::string> notes;
    const std::string saved = app.save_scene(a.save_scene, &notes);
    for (const std::string& n : notes) std::fprintf(stderr, "gui: %s\n", n.c_str());
    std::fprintf(stderr, "gui: %s\n", saved.c_str());
  }
  if (a.stats) print_stats(app, run, host.gl_renderer(), width, height);
  return 0;
#endif
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<GuiArgs>();
  CLI::App* cmd = root.add_subcommand(
      "gui",
      "The interactive tuner: a window to tune m, kappa, gamma (mass unit/s) and dt (s) and "
      "watch, live, whether the mesh stays stable and where the paper's bounds lie.");
  cmd->add_option("scene", a->scene,
                  "scene file or name (default: the last one, else paper-plane)");
  cmd->add_option("--frames", a->frames, "play N frames, then exit")
      ->check(whole_range(1, 10000000));
  cmd->add_option("--screenshot", a->screenshot, "save the window after the last frame (PNG)");
  cmd->add_option("--size", a->size, "window size WxH in pixels (default 1600x1000)");
  cmd->add_option("--steps-per-frame", a->steps_per_frame, "steps per frame while playing")
      ->check(whole_range(1, 10000));
  cmd->add_flag("--stats", a->stats,
                "print one JSON line: frames, iterations, mean frame time, steps per second");
  cmd->add_option("--config-dir", a->config_dir,
                  "settings folder (default $XDG_CONFIG_HOME/dampbound or ~/.config/dampbound)");
  cmd->add_flag("--play", a->play, "start playing");
  // Hidden (no group): every frame sleeps this long, so that input lands within one frame
  // (tests/cli/gui_state.sh's key tap).
  cmd->add_option("--debug-frame-sleep", a->debug_frame_sleep_ms, "")
      ->check(whole_range(0, 10000))
      ->group("");
  cmd->add_option("--tab", a->tab,
                  "open this tab first: status, criteria, pins, suggest, worst, save, mesh or map")
      ->check(CLI::IsMember(
          {"status", "criteria", "pins", "suggest", "worst", "save", "mesh", "map"}));
  cmd->add_option("--frame-dt", a->frame_dt,
                  "the Suggest tab's frame time F (s; default 1/60): its substeps n, dt = F/n; "
                  "with --tab suggest and --frames they are computed at the first frame")
      ->check(finite_positive());
  cmd->add_option("--linearise", a->linearise,
                  "linearise the exact analysis at rest, the current state or the static "
                  "equilibrium (the Criteria tab's choice; remembered)")
      ->check(CLI::IsMember({"rest", "state", "equilibrium"}));
  cmd->add_option("--pin", a->pins,
                  "before the first frame, run KEY=VALUE[,KEY=VALUE...] (m, kappa, gamma, dt, "
                  "policy, factor, integrator, max_iterations, name) to its verdict and pin it; "
                  "repeatable")
      ->allow_extra_args(false);  // one KEY=VALUE list per --pin: a scene after it stays a scene
  cmd->add_option("--save-scene", a->save_scene,
                  "at exit, save the scene, its parameters and the pins with what they measured "
                  "as [[run]]/[[expect]] tables (dampbound check FILE replays them)");
  cmd->add_option("--expect-iterations", a->expect_iterations,
                  "--save-scene: the verdict's iteration may move +- this many iterations")
      ->check(whole_range(0, 100000000))
      ->capture_default_str();
  cmd->add_option("--expect-displacement", a->expect_displacement,
                  "--save-scene: max_displacement_below = this x the measured one (1: none)")
      ->check(number_range(1.0, 1e6))
      ->capture_default_str();
  cmd->add_option("--export", a->export_dir,
                  "with --frames: at the last frame, export the plots (PNG) and data (CSV) to "
                  "this folder, as the Export button does");
  cmd->add_option("--export-prefix", a->export_prefix, "file prefix of --export")
      ->capture_default_str();
  cmd->add_flag("--export-unfinished", a->export_unfinished,
                "--export and the Export button include the current run before its verdict "
                "(by default it is exported only once it reached the limit, settled or diverged)");
  cmd->add_flag("--demo", a->demo,
                "pin a run at a quarter of the lower bound and one at it before the first frame");
  cmd->add_flag("--self-test", a->self_test,
                "operate every widget on each shipped scene (the cut tool included), then let a "
                "seeded random monkey loose; prints the widgets visited; exit 0 when nothing "
                "aborted or hung");
  cmd->add_option("--self-test-scenes", a->self_test_scenes,
                  "--self-test: the scenes visited (default: every shipped scene)");
  cmd->add_option("--monkey-scenes", a->monkey_scenes, "--self-test: the monkey's scenes")
      ->capture_default_str();
  cmd->add_option("--monkey-events", a->monkey_events, "--self-test: input events per scene")
      ->check(whole_range(0, 100000000))
      ->capture_default_str();
  cmd->add_option("--monkey-seed", a->monkey_seed, "--self-test: the monkey's seed")
      ->capture_default_str();
  add_factor_budget_option(cmd, a->factor_budget);
  a->flags.add_to(cmd, true);
  return [a] { return run(*a); };
}

const bool registered = register_command("gui", setup);

}  // namespace
}  // namespace dampbound::app::cmd_ui_gui
