#pragma once
// What the tuner window remembers between runs: the last scene, parameters and options (a
// small text file of `key = value` lines), next to ImGui's window layout (imgui.ini), in
// $XDG_CONFIG_HOME/dampbound (default ~/.config/dampbound) or a --config-dir. A corrupt
// file is ignored with a one-line warning, never a crash. No GL (tests/ui/settings_test.cpp).
#include <optional>
#include <string>

#include "core/params.hpp"

namespace dampbound::ui {

/// The tuner's remembered state. Unset optionals mean "the scene's own".
struct GuiSettings {
  std::string scene_path;        ///< last scene file ("" = the default scene)
  std::optional<Params> params;  ///< last parameters used with scene_path
  std::optional<int> max_iterations;
  int steps_per_frame = 10;
  bool pause_at_verdict = false;
  bool log_y = false;    ///< displacement plot on a log10 axis
  bool show_max = true;  ///< plot the max displacement over all nodes
  bool exact_at_state = false;  ///< exact analysis linearised at the current state
  bool show_springs = true;
  bool show_anchors = false;
  float point_size = 5.0f;  ///< node size in the mesh view (pixels)
  std::string export_dir;   ///< "" = the current directory
  std::string export_prefix = "dampbound";
  int window_width = 0, window_height = 0;  ///< 0: the default size
};

/// The defaults (no scene, the scene's own parameters, 10 steps per frame).
GuiSettings default_gui_settings();

/// The folder for the settings: `override_dir` when not empty, else $XDG_CONFIG_HOME/dampbound
/// when XDG_CONFIG_HOME is set and absolute, else $HOME/.config/dampbound, else "".
std::string config_dir(const std::string& override_dir);

/// The settings as text: a first line "dampbound-gui-settings 1", then `key = value` lines.
/// Numbers round-trip exactly.
std::string serialize_settings(const GuiSettings& s);

/// Parses serialize_settings() output. Unknown keys are skipped (a newer version may add
/// some); a missing header, a line without '=', a bad number, NaN, invalid parameters or a
/// value out of range make the whole text corrupt: nullopt and *error = "line N: reason".
std::optional<GuiSettings> parse_settings(const std::string& text, std::string* error);

/// Reads `path`. A missing file gives the defaults silently; an unreadable or corrupt one
/// gives the defaults and sets *warning to one line naming the file.
GuiSettings load_gui_settings(const std::string& path, std::string* warning);

/// Writes `path` atomically (temporary file, then rename), creating its folder. Throws
/// InputError naming the path when it cannot.
void save_gui_settings(const GuiSettings& s, const std::string& path);

/// True when `text` looks like an ImGui ini file: printable text whose non-empty lines are
/// "[Type][Name]" headers or "Key=Value" entries. Used to skip a corrupt imgui.ini.
bool imgui_ini_looks_valid(const std::string& text);

/// Reads the whole file into *text; false when it cannot be opened.
bool read_text_file(const std::string& path, std::string* text);

}  // namespace dampbound::ui
