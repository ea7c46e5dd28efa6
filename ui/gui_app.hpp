#pragma once
// The interactive tuner window: parameter panel, mesh view, bound envelope and
// displacement plots, status, pinned runs and export. One frame function serves the GLFW
// window and the headless EGL host; the physics is core's Session behind ui/tuner.hpp.
#include <imgui.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/scene.hpp"
#include "ui/frame_renderer.hpp"
#include "ui/mesh_view.hpp"
#include "ui/settings.hpp"
#include "ui/tuner.hpp"
#include "ui/tuner_map.hpp"
#include "ui/tuner_plots.hpp"
#include "ui/tuner_save.hpp"

namespace dampbound::ui {

/// Below this window height (pixels) the layout is compact: the parameters take the whole
/// left column (they need about 560 px, 62 % of the height) and the Status and Criteria tabs
/// join the runs' tabs.
constexpr float kCompactLayoutHeight = 900.0f;

/// How the window starts.
struct GuiOptions {
  std::string config_dir;  ///< settings and imgui.ini live here; "" = nothing persisted
  std::string scenes_dir;  ///< its *.toml files fill the scene picker
  std::optional<SceneSpec>
      scene;  ///< given on the command line; else the last one, else paper-plane
  /// Command-line parameter flags, applied over the scene's (or remembered) parameters.
  std::function<void(Params&, StopRules&)> overrides;
  int steps_per_frame = 0;  ///< > 0: overrides the remembered value
  bool play = false;        ///< start playing
  bool demo = false;        ///< pin two runs (below and at the lower bound) before frame 0
  bool scripted = false;    ///< ignore the mouse (--frames runs: no stray hover tooltips)
  /// The host's clear colour; windows take it as their background (RGBA 0..1).
  std::array<float, 4> background = gui_render_options().clear_color;
};

/// Frame statistics of the window.
struct GuiStats {
  int frames = 0;
  double frame_ms = 0;          ///< smoothed wall time between frames
  double steps_per_second = 0;  ///< smoothed
  double step_ms = 0;           ///< smoothed time in step() per frame
};

class GuiApp {
 public:
  /// Loads the settings and the scene (command line, else the last one, else paper-plane),
  /// applies the overrides, runs the demo when asked. Needs no GL context.
  explicit GuiApp(GuiOptions options);
  ~GuiApp();
  GuiApp(const GuiApp&) = delete;
  GuiApp& operator=(const GuiApp&) = delete;

  /// Builds one frame (call between NewFrame and Render, GL context current).
  void frame(FrameInfo& info);
  /// A FrameFn calling frame() on this app.
  FrameFn frame_fn();

  /// Writes the settings and the window layout (ImGui context current for the layout).
  void save();
  /// Deletes the GL objects (context current); call before the context goes.
  void release_gl();

  /// The window size remembered from the last session (0, 0 when none).
  std::pair<int, int> remembered_window_size() const {
    return {settings_.window_width, settings_.window_height};
  }

  /// A panel's place: name, position and size in pixels.
  struct WindowRect {
    std::string name;
    float x, y, w, h;
  };
  /// Where the panel `name` was drawn in the last frame (tests).
  std::optional<WindowRect> window_rect(const std::string& name) const {
    for (const WindowRect& r : drawn_)
      if (r.name == name) return r;
    return std::nullopt;
  }

  /// The tuner state and the mesh view (tests drive them).
  Tuner& tuner() { return *tuner_; }
  MeshView& mesh_view() { return mesh_; }
  /// Brings a tab to the front at the next frame: "Status", "Criteria", "Pins & export",
  /// "Suggest", "Save scene", "Mesh" or "Map".
  void select_tab(const std::string& name) { select_tab_ = name; }
  /// Starts the Suggest computation as the button does.
  void start_suggest();
  /// The Suggest computation, and the frame statistics of the window.
  TunerSuggest& suggestions() { return suggest_; }
  const GuiStats& stats() const { return stats_; }
  /// Steps per second from the start of the second frame to the last one: the start-up
  /// (first frame, pins run before it) left out. 0 before the third frame.
  double measured_steps_per_second() const;
  /// The stability map's worker and what it shows.
  TunerMap& map() { return map_; }
  MapView& map_view() { return map_view_; }
  /// Export as the button does: the plots (PNG) and data (CSV) to DIR/PREFIX_*. Call inside a
  /// frame (the PNG is rendered with the current GL context). Returns the summary line;
  /// throws with a one-line reason.
  std::string export_plots(const std::string& dir, const std::string& prefix);
  /// Save as scene with the tolerances of the Save tab; returns the summary line and puts
  /// notes (replayed runs) into *notes. Throws with a one-line reason.
  std::string save_scene(const std::string& path, std::vector<std::string>* notes = nullptr);
  /// The tolerances the Save tab writes [[expect]] entries with.
  ExpectTolerance& save_tolerance() { return save_tolerance_; }
  /// Warnings met at start (a corrupt settings file, a missing scene), one line each.
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// Path of the settings file and of the ImGui layout file ("" when not persisted).
  std::string settings_path() const;
  std::string ini_path() const;

 private:
  void load_layout_once();
  void nearest_font_texture();
  void save_layout_if_needed(bool force);
  void layout_windows(const FrameInfo& info);
  /// ImGui::Begin with the default position and size of the layout.
  bool begin(const char* name, int flags);
  void parameters_panel();
  void scene_picker();
  void playback_controls();
  void status_panel();
  void runs_panel();
  void criteria_panel();
  void suggest_panel();
  void save_panel();
  void map_panel();
  void lower_bound_line(double gamma);
  void plots_envelope();
  void plots_displacement();
  void run_demo();
  void update_stats();
  GuiSettings current_settings() const;

  GuiOptions options_;
  GuiSettings settings_;
  std::unique_ptr<Tuner> tuner_;
  MeshView mesh_;
  TunerSuggest suggest_;
  TunerMap map_;
  MapView map_view_;
  ExpectTolerance save_tolerance_ = default_expect_tolerance();
  std::string save_path_, save_message_;
  std::vector<std::string> save_notes_;
  bool save_failed_ = false;
  double run_start_time_ = -1;  ///< start of the second frame (measured_steps_per_second)
  long long run_start_steps_ = 0;
  TunerPlotOptions plot_options_;
  std::vector<std::string> scene_files_;
  std::vector<std::string> warnings_;
  std::string scene_path_;  ///< file of the current scene ("" when built in code)
  std::string open_path_;   ///< the "open a file" text field
  std::string scene_error_;
  std::string param_error_;
  std::string pin_name_;
  std::string export_dir_, export_prefix_, export_message_;
  bool export_failed_ = false;
  bool layout_loaded_ = false;
  bool reset_layout_ = false;
  std::vector<WindowRect> layout_;
  std::vector<WindowRect> follow_;   ///< where panels go this frame after a resize
  float layout_w_ = 0, layout_h_ = 0;  ///< the window size drawn_ was laid out in
  std::vector<WindowRect> drawn_;    ///< where each window was last frame
  std::vector<std::string> hidden_;  ///< panels not drawn in this layout (compact: Status)
  int window_w_ = 0, window_h_ = 0;  ///< size of the last frame
  std::string select_tab_;
  ImTextureID patched_font_texture_ = nullptr;
  GuiStats stats_;
  double last_frame_time_ = -1;
  long long last_steps_ = 0;
  double last_step_seconds_ = 0;
};

}  // namespace dampbound::ui
