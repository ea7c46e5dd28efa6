#include "ui/settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "ui/text_wrap.hpp"

namespace dampbound::ui {

namespace {

const char* const kHeader = "dampbound-gui-settings 1";

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

bool parse_double(const std::string& v, double& out) {
  if (v.empty()) return false;
  char* end = nullptr;
  out = std::strtod(v.c_str(), &end);
  return end != nullptr && *end == '\0' && std::isfinite(out);
}

bool parse_bool(const std::string& v, bool& out) {
  if (v == "true" || v == "1")
    out = true;
  else if (v == "false" || v == "0")
    out = false;
  else
    return false;
  return true;
}

/// A number within [row.lo, row.hi] (any finite value when lo == hi).
bool in_range(const SettingRow& row, double v) {
  return row.lo == row.hi || (v >= row.lo && v <= row.hi);
}

bool parse_int(const SettingRow& row, const std::string& v, int& out) {
  double d = 0;
  if (!parse_double(v, d) || d != std::floor(d) || !in_range(row, d)) return false;
  out = static_cast<int>(d);
  return true;
}

/// The visitor of a SettingField: one call per alternative.
template <class... F>
struct Overload : F... {
  using F::operator()...;
};
template <class... F>
Overload(F...) -> Overload<F...>;

/// True for the rows that live in GuiSettings::params.
bool is_param(const SettingRow& row) {
  return std::visit(
      Overload{[](auto GuiSettings::*) { return false; }, [](auto Params::*) { return true; }},
      row.field);
}

/// A finite number within the row's range.
bool parse_real(const SettingRow& row, const std::string& text, double& out) {
  return parse_double(text, out) && in_range(row, out);
}

/// Reads `text` into the row's field of `s` (or of `p`, the parameters being read); false
/// when the text is not a valid value.
bool read_value(const SettingRow& row, const std::string& text, GuiSettings& s, Params& p) {
  const Overload read{
      [&](std::string GuiSettings::*f) {
        s.*f = text;
        return true;
      },
      [&](bool GuiSettings::*f) { return parse_bool(text, s.*f); },
      [&](int GuiSettings::*f) { return parse_int(row, text, s.*f); },
      [&](std::optional<int> GuiSettings::*f) {
        int k = 0;
        if (!parse_int(row, text, k)) return false;
        s.*f = k;
        return true;
      },
      [&](float GuiSettings::*f) {
        double d = 0;
        if (!parse_real(row, text, d)) return false;
        s.*f = static_cast<float>(d);
        return true;
      },
      [&](double Params::*f) { return parse_real(row, text, p.*f); },
      [&](DampingPolicy Params::*f) {
        const auto v = parse_policy(text);
        if (v) p.*f = *v;
        return v.has_value();
      },
      [&](Integrator Params::*f) {
        const auto v = parse_integrator(text);
        if (v) p.*f = *v;
        return v.has_value();
      },
  };
  return std::visit(read, row.field);
}

/// The row's value as the file writes it; nullopt when it is unset (not written).
std::optional<std::string> write_value(const SettingRow& row, const GuiSettings& s) {
  using Text = std::optional<std::string>;
  if (is_param(row) && !s.params) return std::nullopt;
  const Params& p = s.params ? *s.params : default_params();
  const Overload write{
      [&](std::string GuiSettings::*f) -> Text { return s.*f; },
      [&](bool GuiSettings::*f) -> Text { return s.*f ? "true" : "false"; },
      [&](int GuiSettings::*f) -> Text { return std::to_string(s.*f); },
      [&](std::optional<int> GuiSettings::*f) -> Text {
        return s.*f ? Text(std::to_string(*(s.*f))) : std::nullopt;
      },
      [&](float GuiSettings::*f) -> Text { return format_number(s.*f); },
      [&](double Params::*f) -> Text { return format_number(p.*f); },
      [&](DampingPolicy Params::*f) -> Text { return to_string(p.*f); },
      [&](Integrator Params::*f) -> Text { return to_string(p.*f); },
  };
  return std::visit(write, row.field);
}

}  // namespace

const std::vector<SettingRow>& gui_setting_rows() {
  using S = GuiSettings;
  static const std::vector<SettingRow> rows = {
      {"scene", &S::scene_path, 0, 0, ""},
      {"m", &Params::m, 0, 0, nullptr},
      {"kappa", &Params::kappa, 0, 0, nullptr},
      {"gamma", &Params::gamma, 0, 0, nullptr},
      {"dt", &Params::dt, 0, 0, nullptr},
      {"kd", &Params::kd, 0, 0, nullptr},
      {"rayleigh_mass", &Params::rayleigh_mass, 0, 0, nullptr},
      {"rayleigh_stiffness", &Params::rayleigh_stiffness, 0, 0, nullptr},
      {"policy", &Params::policy, 0, 0, nullptr},
      {"factor", &Params::factor, 0, 0, nullptr},
      {"integrator", &Params::integrator, 0, 0, nullptr},
      {"max_iterations", &S::max_iterations, 1, 100000000, nullptr},
      {"steps_per_frame", &S::steps_per_frame, 1, 10000, "10"},
      {"pause_at_verdict", &S::pause_at_verdict, 0, 0, "false"},
      {"log_y", &S::log_y, 0, 0, "false"},
      {"show_max", &S::show_max, 0, 0, "true"},
      {"exact_at_state", &S::exact_at_state, 0, 0, "false"},
      {"exact_at_equilibrium", &S::exact_at_equilibrium, 0, 0, "false"},
      {"show_springs", &S::show_springs, 0, 0, "true"},
      {"show_anchors", &S::show_anchors, 0, 0, "false"},
      {"point_size", &S::point_size, 1, 40, "5"},
      {"export_dir", &S::export_dir, 0, 0, ""},
      {"export_prefix", &S::export_prefix, 0, 0, "dampbound"},
      {"window_width", &S::window_width, 0, 16384, "0"},
      {"window_height", &S::window_height, 0, 16384, "0"},
  };
  return rows;
}

GuiSettings::GuiSettings() {
  Params unused = default_params();
  for (const SettingRow& row : gui_setting_rows())
    if (row.fallback != nullptr) read_value(row, row.fallback, *this, unused);
}

GuiSettings default_gui_settings() {
  return GuiSettings{};
}

std::string config_dir(const std::string& override_dir) {
  if (!override_dir.empty()) return override_dir;
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  if (xdg != nullptr && xdg[0] == '/') return std::string(xdg) + "/dampbound";
  const char* home = std::getenv("HOME");
  if (home != nullptr && home[0] != '\0') return std::string(home) + "/.config/dampbound";
  return "";
}

std::string serialize_settings(const GuiSettings& s) {
  std::string out = std::string(kHeader) + "\n";
  for (const SettingRow& row : gui_setting_rows())
    if (const auto v = write_value(row, s)) out += std::string(row.key) + " = " + *v + "\n";
  return out;
}

std::optional<GuiSettings> parse_settings(const std::string& text, std::string* error) {
  auto fail = [&](int line, const std::string& why) -> std::optional<GuiSettings> {
    if (error != nullptr) *error = "line " + std::to_string(line) + ": " + why;
    return std::nullopt;
  };
  GuiSettings s;
  Params p = default_params();
  bool any_param = false;
  std::map<std::string, int> param_line;  // the line of each parameter, for validate()'s word
  std::istringstream in(text);
  std::string raw;
  int n = 0;
  while (std::getline(in, raw)) {
    ++n;
    if (raw.find('\0') != std::string::npos) return fail(n, "binary data");
    const std::string line = trim(raw);
    if (n == 1) {
      if (line != kHeader) return fail(1, std::string("expected \"") + kHeader + "\"");
      continue;
    }
    if (line.empty() || line[0] == '#') continue;
    const size_t eq = line.find('=');
    if (eq == std::string::npos) return fail(n, "expected key = value");
    const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
    const auto& rows = gui_setting_rows();
    const auto row =
        std::find_if(rows.begin(), rows.end(), [&](const SettingRow& r) { return key == r.key; });
    if (row == rows.end()) continue;
    any_param |= is_param(*row);
    if (is_param(*row)) param_line[row->key] = n;
    if (!read_value(*row, value, s, p))
      return fail(n, "bad value for " + shorten(key, 60) + ": '" + shorten(value, 60) + "'");
  }
  if (n == 0) return fail(1, "empty file");
  if (any_param) {
    // validate() names the parameter first ("dt must be > 0"): point at its line.
    if (const auto why = validate(p)) {
      const auto at = param_line.find(why->substr(0, why->find(' ')));
      return fail(at != param_line.end() ? at->second : n, *why);
    }
    s.params = p;
  }
  return s;
}

bool read_text_file(const std::string& path, std::string* text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  *text = ss.str();
  return true;
}

GuiSettings load_gui_settings(const std::string& path, std::string* warning) {
  std::error_code ec;
  if (path.empty() || !std::filesystem::exists(path, ec)) return default_gui_settings();
  std::string text, why;
  if (!read_text_file(path, &text)) {
    if (warning != nullptr) *warning = "cannot read settings file " + path + "; using defaults";
    return default_gui_settings();
  }
  const auto s = parse_settings(text, &why);
  if (!s) {
    if (warning != nullptr)
      *warning = "ignoring corrupt settings file " + path + " (" + why +
                 "); using defaults and leaving the file as it is";
    return default_gui_settings();
  }
  return *s;
}

void save_gui_settings(const GuiSettings& s, const std::string& path) {
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  const std::string text = serialize_settings(s);
  write_file_atomic(path, [&](std::ostream& out) { out << text; });
}

bool imgui_ini_looks_valid(const std::string& text) {
  std::istringstream in(text);
  std::string raw;
  while (std::getline(in, raw)) {
    const std::string line = trim(raw);
    if (line.empty() || line[0] == ';') continue;
    for (const char c : line)
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t') return false;
    if (line[0] == '[') {
      if (line.back() != ']' || line.find("][") == std::string::npos) return false;
    } else if (line.find('=') == std::string::npos || line[0] == '=') {
      return false;
    }
  }
  return true;
}

}  // namespace dampbound::ui
