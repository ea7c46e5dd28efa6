#pragma once
// What the tuner window remembers between runs: the last scene, parameters and options (a
// small text file of `key = value` lines), next to ImGui's window layout (imgui.ini), in
// $XDG_CONFIG_HOME/dampbound (default ~/.config/dampbound) or a --config-dir. A corrupt
// file is ignored with a one-line warning, never a crash. No GL (tests/ui/settings_test.cpp).
//
// Every option is one row of one table (gui_setting_rows()): its key, where it lives, its
// valid range and its default. Reading, checking, writing and the defaults all loop over
// that table, so a new option is a field here and a row there.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "dampbound/physics/params.hpp"

namespace dampbound::ui {

/// The tuner's remembered state. Unset optionals mean "the scene's own". A default-constructed
/// value holds the table's defaults.
struct GuiSettings {
  GuiSettings();
  std::string scene_path;        ///< last scene file ("" = the default scene)
  std::optional<Params> params;  ///< last parameters used with scene_path
  std::optional<int> max_iterations;
  int steps_per_frame;  ///< steps drawn per frame while playing
  bool pause_at_verdict;
  bool log_y;           ///< displacement plot on a log10 axis
  bool show_max;        ///< plot the max displacement over all nodes
  bool exact_at_state;  ///< exact analysis linearised at the current state
  bool exact_at_equilibrium;  ///< exact analysis at the static equilibrium (wins over the state)
  bool show_springs;
  bool show_anchors;
  float point_size;        ///< node size in the mesh view (pixels)
  std::string export_dir;  ///< "" = the current directory
  std::string export_prefix;
  int window_width, window_height;  ///< pixels; 0: the default size
};

/// Where one option lives: a member of GuiSettings, or of its Params (the parameter rows,
/// written only when the settings hold parameters). The alternative says how the value is
/// read and written: text as is, numbers range-checked, flags true/false, enums by name.
using SettingField =
    std::variant<std::string GuiSettings::*, bool GuiSettings::*, int GuiSettings::*,
                 std::optional<int> GuiSettings::*, float GuiSettings::*, double Params::*,
                 DampingPolicy Params::*, Integrator Params::*>;

/// One option of the settings file.
struct SettingRow {
  const char* key;
  SettingField field;
  double lo = 0, hi = 0;  ///< numbers: valid range, inclusive (lo == hi: any finite value)
  const char* fallback;   ///< the default, as the file writes it; nullptr: unset
};

/// The options in file order.
const std::vector<SettingRow>& gui_setting_rows();

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
