#include "ui/settings.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "core/io/files.hpp"
#include "core/io/format.hpp"

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

bool parse_int(const std::string& v, int& out, int lo, int hi) {
  double d = 0;
  if (!parse_double(v, d) || d != std::floor(d) || d < lo || d > hi) return false;
  out = static_cast<int>(d);
  return true;
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

const char* b(bool v) {
  return v ? "true" : "false";
}

}  // namespace

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
  std::ostringstream o;
  o << kHeader << "\n";
  o << "scene = " << s.scene_path << "\n";
  if (s.params) {
    const Params& p = *s.params;
    o << "m = " << format_number(p.m) << "\n";
    o << "kappa = " << format_number(p.kappa) << "\n";
    o << "gamma = " << format_number(p.gamma) << "\n";
    o << "dt = " << format_number(p.dt) << "\n";
    o << "policy = " << to_string(p.policy) << "\n";
    o << "factor = " << format_number(p.factor) << "\n";
    o << "integrator = " << to_string(p.integrator) << "\n";
  }
  if (s.max_iterations) o << "max_iterations = " << *s.max_iterations << "\n";
  o << "steps_per_frame = " << s.steps_per_frame << "\n";
  o << "pause_at_verdict = " << b(s.pause_at_verdict) << "\n";
  o << "log_y = " << b(s.log_y) << "\n";
  o << "show_max = " << b(s.show_max) << "\n";
  o << "exact_at_state = " << b(s.exact_at_state) << "\n";
  o << "show_springs = " << b(s.show_springs) << "\n";
  o << "show_anchors = " << b(s.show_anchors) << "\n";
  o << "point_size = " << format_number(s.point_size) << "\n";
  o << "export_dir = " << s.export_dir << "\n";
  o << "export_prefix = " << s.export_prefix << "\n";
  o << "window_width = " << s.window_width << "\n";
  o << "window_height = " << s.window_height << "\n";
  return o.str();
}

std::optional<GuiSettings> parse_settings(const std::string& text, std::string* error) {
  auto fail = [&](int line, const std::string& why) -> std::optional<GuiSettings> {
    if (error != nullptr) *error = "line " + std::to_string(line) + ": " + why;
    return std::nullopt;
  };
  GuiSettings s;
  Params p = default_params();
  bool any_param = false;
  std::istringstream in(text);
  std::string raw;
  int n = 0;
  // Each known key parses its value into s (or p); false means a bad value.
  const std::map<std::string, std::function<bool(const std::string&)>> keys = {
      {"scene",
       [&](const std::string& v) {
         s.scene_path = v;
         return true;
       }},
      {"m",
       [&](const std::string& v) {
         any_param = true;
         return parse_double(v, p.m);
       }},
      {"kappa",
       [&](const std::string& v) {
         any_param = true;
         return parse_double(v, p.kappa);
       }},
      {"gamma",
       [&](const std::string& v) {
         any_param = true;
         return parse_double(v, p.gamma);
       }},
      {"dt",
       [&](const std::string& v) {
         any_param = true;
         return parse_double(v, p.dt);
       }},
      {"factor",
       [&](const std::string& v) {
         any_param = true;
         return parse_double(v, p.factor);
       }},
      {"policy",
       [&](const std::string& v) {
         any_param = true;
         const auto pol = parse_policy(v);
         if (pol) p.policy = *pol;
         return pol.has_value();
       }},
      {"integrator",
       [&](const std::string& v) {
         any_param = true;
         const auto i = parse_integrator(v);
         if (i) p.integrator = *i;
         return i.has_value();
       }},
      {"max_iterations",
       [&](const std::string& v) {
         int k = 0;
         if (!parse_int(v, k, 1, 100000000)) return false;
         s.max_iterations = k;
         return true;
       }},
      {"steps_per_frame",
       [&](const std::string& v) { return parse_int(v, s.steps_per_frame, 1, 10000); }},
      {"pause_at_verdict", [&](const std::string& v) { return parse_bool(v, s.pause_at_verdict); }},
      {"log_y", [&](const std::string& v) { return parse_bool(v, s.log_y); }},
      {"show_max", [&](const std::string& v) { return parse_bool(v, s.show_max); }},
      {"exact_at_state",
       [&](const std::string& v) { return parse_bool(v, s.exact_at_state); }},
      {"show_springs", [&](const std::string& v) { return parse_bool(v, s.show_springs); }},
      {"show_anchors", [&](const std::string& v) { return parse_bool(v, s.show_anchors); }},
      {"point_size",
       [&](const std::string& v) {
         double d = 0;
         if (!parse_double(v, d) || d < 1 || d > 40) return false;
         s.point_size = static_cast<float>(d);
         return true;
       }},
      {"export_dir",
       [&](const std::string& v) {
         s.export_dir = v;
         return true;
       }},
      {"export_prefix",
       [&](const std::string& v) {
         s.export_prefix = v;
         return true;
       }},
      {"window_width",
       [&](const std::string& v) { return parse_int(v, s.window_width, 0, 16384); }},
      {"window_height",
       [&](const std::string& v) { return parse_int(v, s.window_height, 0, 16384); }},
  };
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
    const auto it = keys.find(key);
    if (it == keys.end()) continue;
    if (!it->second(value)) return fail(n, "bad value for " + key + ": '" + value + "'");
  }
  if (n == 0) return fail(1, "empty file");
  if (any_param) {
    const std::string why = validate(p);
    if (!why.empty()) return fail(n, why);
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
      *warning = "ignoring corrupt settings file " + path + " (" + why + "); using defaults";
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
