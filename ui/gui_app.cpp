#include "ui/gui_app.hpp"

#include <GL/gl.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <utility>

#include "core/io/files.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/physics/bounds.hpp"
#include "ui/gui_items.hpp"

namespace dampbound::ui {

namespace {
double now_s() {
  using Clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

void warn(std::vector<std::string>& out, const std::string& long_text) {
  const std::string text = shorten(long_text, 400);
  out.push_back(text);
  std::fprintf(stderr, "dampbound: warning: %s\n", text.c_str());
}
}  // namespace

template <class Link>
void GuiApp::link_settings(GuiSettings& s, Link&& link) {
  link(s.steps_per_frame, tuner_->playback().steps_per_frame);
  link(s.pause_at_verdict, tuner_->playback().pause_at_verdict);
  link(s.log_y, plot_options_.log_y);
  link(s.show_max, plot_options_.show_max);
  link(s.show_springs, mesh_.options.show_springs);
  link(s.show_anchors, mesh_.options.show_anchors);
  link(s.point_size, mesh_.options.point_size);
  link(s.export_dir, runs_.export_dir);
  link(s.export_prefix, runs_.export_prefix);
}

GuiApp::GuiApp(GuiOptions options) : options_(std::move(options)) {
  std::string warning;
  if (!options_.config_dir.empty()) settings_ = load_gui_settings(settings_path(), &warning);
  if (!warning.empty()) warn(warnings_, warning);
  keep_settings_file_ = !warning.empty();
  std::error_code ec;
  if (!options_.scenes_dir.empty()) {
    for (const auto& e : std::filesystem::directory_iterator(options_.scenes_dir, ec))
      if (e.path().extension() == ".toml") scene_.files.push_back(e.path().string());
    std::sort(scene_.files.begin(), scene_.files.end());
  }
  std::optional<SceneSpec> scene = options_.scene;
  bool remembered = false;
  if (!scene && !settings_.scene_path.empty()) {
    try {
      scene = load_scene(settings_.scene_path);
      remembered = true;
    } catch (const std::exception& e) {
      warn(warnings_, std::string("cannot reopen the last scene: ") + e.what());
    }
  }
  if (!scene) {
    const std::string plane = options_.scenes_dir + "/paper-plane.toml";
    try {
      scene = load_scene(plane);
    } catch (const std::exception&) {
      scene = paper_plane_scene();
      scene->name += " (built in)";
    }
  }
  scene_.path = scene_.typed = scene->path;
  tuner_ = std::make_unique<Tuner>(std::move(*scene));
  shown_scene_version_ = tuner_->scene_version();
  Params p = tuner_->params();
  StopRules r = tuner_->session().rules();
  if (remembered && settings_.params) p = *settings_.params;
  if (remembered && settings_.max_iterations) r.max_iterations = *settings_.max_iterations;
  if (options_.overrides) options_.overrides(p, r);
  std::string why;
  if (!tuner_->set_params(p, &why)) warn(warnings_, "ignoring parameters: " + why);
  tuner_->set_max_iterations(r.max_iterations);
  tuner_->reset();
  link_settings(settings_, [](const auto& saved, auto& live) { live = saved; });
  tuner_->criteria_state().set_linearisation(settings_.exact_at_equilibrium
                                                 ? Linearisation::equilibrium
                                             : settings_.exact_at_state ? Linearisation::state
                                                                        : Linearisation::rest);
  if (options_.linearise) tuner_->criteria_state().set_linearisation(*options_.linearise);
  tuner_->criteria_state().set_factor_budget(options_.factor_budget);
  // A person's window never holds a frame for the analysis; a scripted run shows its result.
  if (!options_.scripted) tuner_->criteria_state().set_frame_wait(kCriteriaFrameWait);
  suggest_.set_factor_budget(options_.factor_budget);
  knobs_.set_factor_budget(options_.factor_budget);
  substeps_.set_factor_budget(options_.factor_budget);
  if (options_.steps_per_frame > 0) tuner_->playback().steps_per_frame = options_.steps_per_frame;
  if (options_.demo) run_demo();
  if (options_.play) tuner_->set_playing(true);
  if (!warnings_.empty()) tuner_->set_notice(warnings_.back());
}

GuiApp::~GuiApp() = default;

std::string GuiApp::settings_path() const {
  return options_.config_dir.empty() ? "" : options_.config_dir + "/settings.txt";
}

std::string GuiApp::ini_path() const {
  return options_.config_dir.empty() ? "" : options_.config_dir + "/imgui.ini";
}

void GuiApp::run_demo() {
  // Two runs pinned for comparison, as in the paper's Fig. 1: damping below the lower bound
  // (eq. 5) and at it. The current run then starts over with the chosen parameters. Each
  // pinned run goes to its limit, so that it carries its settled-rule verdict (SPEC 8).
  const Params base = tuner_->params();
  const double lo = lower_bound(base.m, base.kappa);
  const int steps = tuner_->session().rules().max_iterations;
  auto pin_run = [&](double gamma, const std::string& name) {
    Params p = base;
    p.gamma = gamma;
    p.policy = DampingPolicy::fixed;
    tuner_->set_params(p);
    tuner_->reset();
    tuner_->step(steps);
    tuner_->pin(name + " = " + fmt(gamma));
  };
  pin_run(lo / 4, "gamma = lower / 4");
  pin_run(lo, "gamma = lower");
  tuner_->set_params(base);
  tuner_->reset();
}

GuiSettings GuiApp::current_settings() {
  GuiSettings s = settings_;
  link_settings(s, [](auto& saved, const auto& live) { saved = live; });
  s.scene_path = scene_.path;
  s.params = tuner_->params();
  s.max_iterations = tuner_->session().rules().max_iterations;
  s.exact_at_state = tuner_->criteria_state().at_current_state();
  s.exact_at_equilibrium = tuner_->criteria_state().linearisation() == Linearisation::equilibrium;
  return s;
}

void GuiApp::load_layout_once() {
  if (ini_loaded_) return;
  ini_loaded_ = true;
  if (options_.scripted) ImGui::GetIO().ConfigFlags |= ImGuiConfigFlags_NoMouse;
  const auto& bg = options_.background;
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg] = ImVec4(bg[0], bg[1], bg[2], 1.0f);
  const std::string path = ini_path();
  std::string text;
  if (path.empty() || !read_text_file(path, &text)) return;
  if (!imgui_ini_looks_valid(text)) {
    warn(warnings_, "ignoring corrupt window layout file " + path);
    tuner_->set_notice(warnings_.back());
    return;
  }
  ImGui::LoadIniSettingsFromMemory(text.c_str(), text.size());
  // The remembered panels were laid out in a window of the remembered size: when this window
  // has another size, they follow it from the second frame on (layout_windows).
  layout_.set_remembered_size(static_cast<float>(settings_.window_width),
                              static_cast<float>(settings_.window_height));
  layout_.set_remembered_panels(remembered_panels(text));
}

void GuiApp::save_layout_if_needed(bool force) {
  ImGuiIO& io = ImGui::GetIO();
  const std::string path = ini_path();
  if (path.empty() || (!force && !io.WantSaveIniSettings)) return;
  io.WantSaveIniSettings = false;
  size_t size = 0;
  const char* data = ImGui::SaveIniSettingsToMemory(&size);
  try {
    std::error_code ec;
    std::filesystem::create_directories(options_.config_dir, ec);
    write_file_atomic(
        path, [&](std::ostream& out) { out.write(data, static_cast<std::streamsize>(size)); });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dampbound: warning: %s\n", e.what());
  }
}

void GuiApp::save() {
  if (options_.config_dir.empty()) return;
  try {
    if (!keep_settings_file_) save_gui_settings(current_settings(), settings_path());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dampbound: warning: cannot save settings: %s\n", e.what());
  }
  if (ImGui::GetCurrentContext() != nullptr) save_layout_if_needed(true);
}

void GuiApp::nearest_font_texture() {
  // ImGui draws glyphs at whole pixels, one texel per pixel: nearest sampling gives the same
  // image as bilinear, and a software rasteriser shades every pixel of the window with one
  // texel fetch instead of four. Lines then take their anti-aliasing from geometry.
  ImGuiIO& io = ImGui::GetIO();
  const ImTextureID tex = io.Fonts->TexID;
  if (tex == nullptr || tex == nearest_font_texture_) return;
  nearest_font_texture_ = tex;
  ImGui::GetStyle().AntiAliasedLinesUseTex = false;
  GLint bound = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(reinterpret_cast<std::intptr_t>(tex)));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(bound));
}

void GuiApp::release_gl() {
  mesh_.release_gl();
}

void GuiApp::start_suggest() {
  suggest_.start(tuner_->session());
}

void GuiApp::start_knobs() {
  knobs_.start(tuner_->session(), rayleigh_zeta_, tuner_->generation(), tuner_->topology());
}

void GuiApp::drop_stale_knobs() {
  // The ceiling and the pair speak for the parameters and springs they were computed for: a
  // parameter change, a Reset, a cut or another scene drops them (and a computation under way).
  BackgroundJob<KnobsResult>& job = knobs_.job();
  job.poll();
  const Tuner& t = *tuner_;
  if ((job.busy() || job.result()) && !knobs_.current(t.params(), t.generation(), t.topology()))
    job.clear();
}

FrameFn GuiApp::frame_fn() {
  return [this](FrameInfo& info) { frame(info); };
}

void GuiApp::frame(FrameInfo& info) {
  nearest_font_texture();
  load_layout_once();
  if (!info.layout_pass) {  // a layout pass only builds the windows
    meter_.tick(now_s(), tuner_->total_steps(), tuner_->step_seconds());
    settings_.window_width = info.width;
    settings_.window_height = info.height;
    tuner_->advance();
  }
  layout_.update(static_cast<float>(info.width), static_cast<float>(info.height));
  const int fixed = ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse;
  if (layout_.begin("Parameters", 0)) parameters_panel();
  ImGui::End();
  if (tuner_->scene_version() != shown_scene_version_) {
    // Another scene (or the same one resolved anew): no answer of the last one stays on show
    // or applies (Suggest's buttons, the substeps); the criteria forget theirs in the tuner.
    shown_scene_version_ = tuner_->scene_version();
    suggest_.clear();
    substeps_.job().clear();
  }
  suggest_.poll();
  substeps_.job().poll();
  drop_stale_knobs();
  // Below kCompactLayoutHeight the status tabs join the runs' tabs, under short titles (the part
  // after ### is the tab's identity, so a selected tab stays selected across sizes).
  const bool compact = layout_.compact();
  auto tab = [&](const char* name, const char* short_name = nullptr) {
    const bool selected = select_tab_ == name;
    if (selected) select_tab_.clear();
    const std::string label =
        std::string(compact && short_name != nullptr ? short_name : name) + "###" + name;
    return item::begin_tab_item(label.c_str(), selected ? ImGuiTabItemFlags_SetSelected : 0);
  };
  auto status_tabs = [&] {
    if (tab("Status")) {
      status_panel();
      ImGui::EndTabItem();
    }
    if (tab("Criteria")) {
      criteria_panel();
      ImGui::EndTabItem();
    }
  };
  if (!compact) {
    if (layout_.begin("Status", 0) && ImGui::BeginTabBar("status_tabs")) {
      status_tabs();
      ImGui::EndTabBar();
    }
    ImGui::End();
  }
  if (layout_.begin("Mesh view", fixed) && ImGui::BeginTabBar("view_tabs")) {
    if (tab("Mesh")) {
      mesh_.draw(*tuner_);
      ImGui::EndTabItem();
    }
    if (tab("Map")) {
      map_panel();
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
  if (layout_.begin("Damping bounds", fixed)) plots_envelope();
  ImGui::End();
  if (layout_.begin("Displacement", fixed)) plots_displacement();
  ImGui::End();
  if (layout_.begin("Runs", 0) && ImGui::BeginTabBar("runs_tabs")) {
    if (compact) status_tabs();
    if (tab("Pins & export", "Pins")) {
      runs_panel();
      ImGui::EndTabItem();
    }
    if (tab("Suggest")) {
      suggest_panel();
      ImGui::EndTabItem();
    }
    if (tab("Worst nodes", "Worst")) {
      worst_panel();
      ImGui::EndTabItem();
    }
    if (tab("Save scene", "Save")) {
      save_panel();
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
  layout_.end_frame();
  if (!info.layout_pass) save_layout_if_needed(false);
}

}  // namespace dampbound::ui
