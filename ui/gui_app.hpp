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

#include "dampbound/run/scene.hpp"
#include "ui/frame_renderer.hpp"
#include "ui/gui_layout.hpp"
#include "ui/gui_stats.hpp"
#include "ui/gui_widgets.hpp"
#include "ui/mesh_view.hpp"
#include "ui/settings.hpp"
#include "ui/tuner.hpp"
#include "ui/tuner_knobs.hpp"
#include "ui/tuner_map.hpp"
#include "ui/tuner_plots.hpp"
#include "ui/tuner_save.hpp"
#include "ui/tuner_substeps.hpp"
#include "ui/tuner_worst.hpp"

namespace dampbound::ui {

/// How the window starts.
struct GuiOptions {
  std::string config_dir;  ///< settings and imgui.ini live here; "" = nothing persisted
  std::string scenes_dir;  ///< its *.toml files fill the scene picker
  std::optional<SceneSpec>
      scene;  ///< given on the command line; else the last one, else paper-plane
  /// Command-line parameter flags, applied over the scene's (or remembered) parameters.
  std::function<void(Params&, StopRules&)> overrides;
  int steps_per_frame = 0;  ///< > 0: overrides the remembered value
  /// The most one factorisation of the exact analysis and of Suggest may cost (flops).
  double factor_budget = kDefaultFactorBudget;
  /// Where the exact analysis linearises; unset: the remembered choice (rest at first).
  std::optional<Linearisation> linearise;
  bool play = false;        ///< start playing
  bool demo = false;        ///< pin two runs (below and at the lower bound) before frame 0
  bool scripted = false;    ///< ignore the mouse (--frames runs: no stray hover tooltips)
  /// The host's clear colour; windows take it as their background (RGBA 0..1).
  std::array<float, 4> background = gui_render_options().clear_color;
};

/// The scene picker: the scenes of the source tree and a field to open any other file.
struct ScenePickerState {
  std::vector<std::string> files;  ///< the *.toml files of scenes_dir, sorted
  std::string path;                ///< file of the current scene ("" when built in code)
  std::string typed;               ///< the "open a file" text field
  std::string error;               ///< why the last scene did not open
};

/// The "Pins & export" tab: the next pin's name, where Export writes, what it said.
struct RunsPanelState {
  std::string pin_name;
  std::string export_dir, export_prefix;
  bool export_unfinished = false;  ///< export the current run while it still runs
  ActionMessage export_result;
};

/// The "Worst nodes" tab: how many rows, and which order (0: by dt_safe_i, 1: by gamma_safe_i).
struct WorstPanelState {
  int count = 10;
  int order = 0;
};

/// The "Save scene" tab: the tolerances of the [[expect]] entries, the file, what Save said.
struct SavePanelState {
  ExpectTolerance tolerance = default_expect_tolerance();
  std::string path;
  ActionMessage result;
  std::vector<std::string> notes;  ///< runs replayed headless before saving
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

  /// Where the panel `name` was drawn in the last frame (tests).
  std::optional<PanelRect> window_rect(const std::string& name) const {
    return layout_.drawn(name);
  }

  /// The tuner state and the mesh view (tests drive them).
  Tuner& tuner() { return *tuner_; }
  MeshView& mesh_view() { return mesh_; }
  /// Brings a tab to the front at the next frame: "Status", "Criteria", "Pins & export",
  /// "Suggest", "Worst nodes", "Save scene", "Mesh" or "Map".
  void select_tab(const std::string& name) { select_tab_ = name; }
  /// Opens a scene file as the scene picker does (an error shows under the picker).
  void open_scene(const std::string& path);
  /// The file of the current scene ("" when built in code).
  const std::string& scene_path() const { return scene_.path; }
  /// The files of the scene picker's list.
  const std::vector<std::string>& scene_files() const { return scene_.files; }
  /// The folder the Export button writes to.
  void set_export_folder(const std::string& dir) { runs_.export_dir = dir; }
  /// True when the Criteria table, last drawn, had rows below the fold (it scrolled).
  bool criteria_rows_hidden() const { return criteria_rows_hidden_; }
  /// Whether Export includes the current run before its verdict (the tab's checkbox).
  void set_export_unfinished(bool on) { runs_.export_unfinished = on; }
  /// Starts the Suggest computation as the button does.
  void start_suggest();
  /// The Suggest computation, and the frame statistics of the window.
  TunerSuggest& suggestions() { return suggest_; }
  /// Starts the substeps of the Suggest tab for frame_dt() as its button does.
  void start_substeps() { substeps_.start(tuner_->session(), frame_dt_); }
  BackgroundJob<SubstepsResult>& substeps() { return substeps_.job(); }
  /// Starts the stiffness ceiling and the Rayleigh pair as the tab's button does.
  void start_knobs();
  /// Their computation (dropped at the next frame once it no longer speaks for the model).
  BackgroundJob<KnobsResult>& knobs() { return knobs_.job(); }
  /// The ratio the Rayleigh pair asks at both ends of the band (default 0.05).
  void set_rayleigh_zeta(double zeta) { rayleigh_zeta_ = zeta; }
  /// The Suggest tab's frame time (s; default 1/60).
  double frame_dt() const { return frame_dt_; }
  void set_frame_dt(double seconds) { frame_dt_ = seconds; }
  const GuiStats& stats() const { return meter_.stats(); }
  /// Steps per second from the start of the second frame to the last one: the start-up
  /// (first frame, pins run before it) left out. 0 before the third frame.
  double measured_steps_per_second() const { return meter_.measured_steps_per_second(); }
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
  ExpectTolerance& save_tolerance() { return save_.tolerance; }
  /// Warnings met at start (a corrupt settings file, a missing scene), one line each.
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// Path of the settings file and of the ImGui layout file ("" when not persisted).
  std::string settings_path() const;
  std::string ini_path() const;

 private:
  void load_layout_once();
  void nearest_font_texture();
  void save_layout_if_needed(bool force);
  void parameters_panel();
  /// The gamma|zeta toggle and the slider of the chosen one, the other shown beside it.
  void damping_input(Params& p, bool& changed);
  /// kd, rayleigh_mass, rayleigh_stiffness: a checkbox (off: 0) and a log slider each.
  void other_damping_input(Params& p, bool& changed);
  void scene_picker();
  void playback_controls();
  void status_panel();
  void runs_panel();
  void criteria_panel();
  /// The Criteria tab's worker: its stage, seconds, estimate and Cancel.
  void criteria_progress(TunerCriteria& c);
  void suggest_panel();
  void suggest_values();
  /// The Suggest tab's substeps per frame: the frame time, the two counts, apply buttons.
  void substeps_section();
  /// Its SPEC 11 alternative: the mass that makes one step per frame stable, apply, colour.
  void mass_scaling_section(const SubstepsResult& r);
  /// The stiffness ceiling and the Rayleigh pair, with their apply buttons (gui_knobs_panel.cpp).
  void knobs_section();
  void drop_stale_knobs();
  void save_panel();
  void worst_panel();
  void map_panel();
  void plots_envelope();
  void plots_displacement();
  void run_demo();
  /// Calls link(remembered, live) for each setting the frame edits in place: loading the
  /// settings copies one way, saving them the other.
  template <class Link>
  void link_settings(GuiSettings& s, Link&& link);
  GuiSettings current_settings();

  GuiOptions options_;
  GuiSettings settings_;  ///< as loaded; the window size follows the frames
  /// The settings file could not be read or parsed: it is left as it is (not overwritten
  /// with defaults on close), so the user can mend the line the warning names.
  bool keep_settings_file_ = false;
  std::unique_ptr<Tuner> tuner_;
  MeshView mesh_;
  TunerSuggest suggest_;
  std::uint64_t shown_scene_version_ = 0;  ///< the scene the derived panels were made for
  TunerSubsteps substeps_;
  TunerKnobs knobs_;
  double rayleigh_zeta_ = kDefaultRayleighZeta;
  double frame_dt_ = kDefaultFrameDt;
  TunerMap map_;
  MapView map_view_;
  TunerPlotOptions plot_options_;
  GuiLayout layout_;
  FrameMeter meter_;
  bool criteria_rows_hidden_ = false;
  ScenePickerState scene_;
  RunsPanelState runs_;
  SavePanelState save_;
  WorstPanelState worst_;
  TunerWorst worst_nodes_;
  std::string param_error_;
  /// The values of kd, rayleigh_mass, rayleigh_stiffness their sliders keep while off.
  std::array<double, 3> other_damping_{0.001, 0.1, 0.001};  ///< why the last parameter change was not applied
  std::vector<std::string> warnings_;
  std::string select_tab_;  ///< the tab to bring to the front at the next frame
  bool ini_loaded_ = false;
  ImTextureID nearest_font_texture_ = nullptr;  ///< the font texture set to nearest sampling
};

}  // namespace dampbound::ui
