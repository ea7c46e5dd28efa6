// What the tuner remembers (ui/settings.hpp): exact round trip, corrupt files ignored with a
// one-line warning, the config folder, atomic saves.
#include "ui/settings.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>
#include <vector>

namespace dampbound::ui {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("dampbound_settings_test_" + name);
  fs::remove_all(d);
  return d;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

GuiSettings unusual() {
  GuiSettings s;
  s.scene_path = "/some where/odd = name.toml";
  Params p;
  p.m = 0.1 + 0.2;  // not exactly 0.3: must come back bit for bit
  p.kappa = 1.0 / 3.0;
  p.gamma = 0;
  p.dt = 1e-3;
  p.policy = DampingPolicy::upper;
  p.factor = 1.05;
  p.integrator = Integrator::rk4;
  s.params = p;
  s.max_iterations = 12345;
  s.steps_per_frame = 37;
  s.pause_at_verdict = true;
  s.log_y = true;
  s.show_max = false;
  s.exact_at_state = true;
  s.exact_at_equilibrium = true;
  s.show_springs = false;
  s.show_anchors = true;
  s.point_size = 9.5f;
  s.export_dir = "/tmp/out dir";
  s.export_prefix = "fig1_like";
  s.window_width = 1280;
  s.window_height = 800;
  return s;
}

TEST(Settings, RoundTripIsExact) {
  const GuiSettings s = unusual();
  std::string err;
  const auto back = parse_settings(serialize_settings(s), &err);
  ASSERT_TRUE(back) << err;
  EXPECT_EQ(back->scene_path, s.scene_path);
  ASSERT_TRUE(back->params);
  EXPECT_EQ(back->params->m, s.params->m);
  EXPECT_EQ(back->params->kappa, s.params->kappa);
  EXPECT_EQ(back->params->gamma, 0.0);
  EXPECT_EQ(back->params->dt, s.params->dt);
  EXPECT_EQ(back->params->policy, DampingPolicy::upper);
  EXPECT_EQ(back->params->factor, 1.05);
  EXPECT_EQ(back->params->integrator, Integrator::rk4);
  EXPECT_EQ(back->max_iterations, 12345);
  EXPECT_EQ(back->steps_per_frame, 37);
  EXPECT_TRUE(back->pause_at_verdict);
  EXPECT_TRUE(back->log_y);
  EXPECT_FALSE(back->show_max);
  EXPECT_TRUE(back->exact_at_state);
  EXPECT_TRUE(back->exact_at_equilibrium);
  EXPECT_FALSE(back->show_springs);
  EXPECT_TRUE(back->show_anchors);
  EXPECT_EQ(back->point_size, 9.5f);
  EXPECT_EQ(back->export_dir, "/tmp/out dir");
  EXPECT_EQ(back->export_prefix, "fig1_like");
  EXPECT_EQ(back->window_width, 1280);
  EXPECT_EQ(back->window_height, 800);
}

// The file as the hand-written reader and writer of before the settings table wrote it: an
// existing file reads the same, and the same values write the same bytes.
const char* const kGoldenUnusual =
    "dampbound-gui-settings 1\n"
    "scene = /some where/odd = name.toml\n"
    "m = 0.30000000000000004\n"
    "kappa = 0.3333333333333333\n"
    "gamma = 0\n"
    "dt = 0.001\n"
    "kd = 0\n"
    "rayleigh_mass = 0\n"
    "rayleigh_stiffness = 0\n"
    "policy = upper\n"
    "factor = 1.05\n"
    "integrator = rk4\n"
    "max_iterations = 12345\n"
    "steps_per_frame = 37\n"
    "pause_at_verdict = true\n"
    "log_y = true\n"
    "show_max = false\n"
    "exact_at_state = true\n"
    "exact_at_equilibrium = true\n"
    "show_springs = false\n"
    "show_anchors = true\n"
    "point_size = 9.5\n"
    "export_dir = /tmp/out dir\n"
    "export_prefix = fig1_like\n"
    "window_width = 1280\n"
    "window_height = 800\n";

const char* const kGoldenDefaults =
    "dampbound-gui-settings 1\n"
    "scene = \n"
    "steps_per_frame = 10\n"
    "pause_at_verdict = false\n"
    "log_y = false\n"
    "show_max = true\n"
    "exact_at_state = false\n"
    "exact_at_equilibrium = false\n"
    "show_springs = true\n"
    "show_anchors = false\n"
    "point_size = 5\n"
    "export_dir = \n"
    "export_prefix = dampbound\n"
    "window_width = 0\n"
    "window_height = 0\n";

TEST(Settings, WritesTheGoldenFileByteForByte) {
  EXPECT_EQ(serialize_settings(unusual()), kGoldenUnusual);
  EXPECT_EQ(serialize_settings(default_gui_settings()), kGoldenDefaults);
  // And reads it back to the same values, which write the same bytes again.
  const auto back = parse_settings(kGoldenUnusual, nullptr);
  ASSERT_TRUE(back);
  EXPECT_EQ(serialize_settings(*back), kGoldenUnusual);
}

TEST(Settings, EveryRowHasOneKeyAndItsDefaultIsValid) {
  std::vector<std::string> keys;
  for (const SettingRow& row : gui_setting_rows()) {
    for (const std::string& k : keys) EXPECT_NE(k, row.key);
    keys.push_back(row.key);
    // Only what may be unset (the parameters, an optional, text) goes without a default.
    const bool may_be_unset =
        std::holds_alternative<std::optional<int> GuiSettings::*>(row.field) ||
        std::holds_alternative<std::string GuiSettings::*>(row.field) ||
        std::holds_alternative<double Params::*>(row.field) ||
        std::holds_alternative<DampingPolicy Params::*>(row.field) ||
        std::holds_alternative<Integrator Params::*>(row.field);
    EXPECT_TRUE(row.fallback != nullptr || may_be_unset) << row.key;
    if (row.fallback == nullptr) continue;
    // The default parses on its own line.
    std::string err;
    EXPECT_TRUE(parse_settings(
        std::string("dampbound-gui-settings 1\n") + row.key + " = " + row.fallback + "\n", &err))
        << row.key << ": " << err;
  }
}

TEST(Settings, OutOfRangeValuesAreRefusedPerOption) {
  const std::string head = "dampbound-gui-settings 1\n";
  for (const char* line :
       {"max_iterations = 0", "max_iterations = 100000001", "steps_per_frame = 10001",
        "point_size = 0.5", "point_size = 41", "window_width = -1", "window_height = 16385",
        "integrator = euler", "show_max = yes", "dt = inf"}) {
    std::string err;
    EXPECT_FALSE(parse_settings(head + line + "\n", &err)) << line;
    const std::string key = std::string(line).substr(0, std::string(line).find(' '));
    EXPECT_EQ(err.rfind("line 2: bad value for " + key + ": '", 0), 0u) << err;
  }
  for (const char* line : {"max_iterations = 1", "steps_per_frame = 10000", "point_size = 40",
                           "window_width = 16384", "show_max = 0"})
    EXPECT_TRUE(parse_settings(head + line + "\n", nullptr)) << line;
}

TEST(Settings, DefaultsRoundTripWithoutParameters) {
  const auto back = parse_settings(serialize_settings(default_gui_settings()), nullptr);
  ASSERT_TRUE(back);
  EXPECT_FALSE(back->params);
  EXPECT_FALSE(back->max_iterations);
  EXPECT_EQ(back->steps_per_frame, 10);
}

TEST(Settings, CorruptTextIsRejectedWithTheLine) {
  const std::string head = "dampbound-gui-settings 1\n";
  const std::pair<std::string, std::string> bad[] = {
      {"", "line 1"},
      {"hello\nm = 1\n", "line 1"},
      {head + "m = abc\n", "line 2"},
      {head + "steps_per_frame = 3\ngamma = nan\n", "line 3"},
      {head + "m = -1\n", "m must be"},
      {head + "steps_per_frame = 0\n", "line 2"},
      {head + "steps_per_frame = 2.5\n", "line 2"},
      {head + "log_y = maybe\n", "line 2"},
      {head + "just some words\n", "line 2"},
      {head + "policy = wobbly\n", "line 2"},
      {head + std::string("m = 1\0\x01\x02", 8) + "\n", "line 2"},
  };
  for (const auto& [text, where] : bad) {
    std::string err;
    EXPECT_FALSE(parse_settings(text, &err)) << text;
    EXPECT_NE(err.find(where), std::string::npos) << err;
  }
}

TEST(Settings, AValueRefusedByTheParametersCheckIsReportedAtItsOwnLine) {
  // The check of the parameters together runs after the last line: it names the line of the
  // parameter it refuses, not the file's last line.
  const std::string text =
      "dampbound-gui-settings 1\nm = 1\ngamma = -1\ndt = 0.1\nlog_y = true\nshow_max = true\n";
  std::string err;
  EXPECT_FALSE(parse_settings(text, &err));
  EXPECT_EQ(err.rfind("line 3: gamma must be >= 0", 0), 0u) << err;
}

TEST(Settings, UnknownKeysAndCommentsAreSkipped) {
  const auto s = parse_settings(
      "dampbound-gui-settings 1\n# a comment\nfuture_key = 7\n\nsteps_per_frame = 3\n", nullptr);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->steps_per_frame, 3);
}

TEST(Settings, LoadMissingIsSilentCorruptWarnsOnOneLine) {
  const fs::path d = fresh_dir("load");
  std::string warning;
  const GuiSettings a = load_gui_settings((d / "settings.txt").string(), &warning);
  EXPECT_TRUE(warning.empty());
  EXPECT_EQ(a.steps_per_frame, 10);
  write(d / "settings.txt", "\x89PNG garbage\n\x01\x02");
  const GuiSettings b = load_gui_settings((d / "settings.txt").string(), &warning);
  EXPECT_NE(warning.find("settings.txt"), std::string::npos);
  EXPECT_EQ(warning.find('\n'), std::string::npos);
  EXPECT_EQ(b.steps_per_frame, 10);
  warning.clear();
  fs::create_directories(d / "adir.txt");  // exists but is not a readable file
  load_gui_settings((d / "adir.txt").string(), &warning);
  EXPECT_FALSE(warning.empty());
  fs::remove_all(d);
}

TEST(Settings, AFiveMegabyteLineWarnsShortly) {
  // The warning is shown in the tuner and printed: a 5 MB bad value is not repeated in it.
  const fs::path d = fresh_dir("long");
  write(d / "settings.txt",
        "dampbound-gui-settings 1\nsteps_per_frame = " + std::string(5 << 20, '7') + "x\n");
  std::string warning;
  const GuiSettings s = load_gui_settings((d / "settings.txt").string(), &warning);
  EXPECT_EQ(s.steps_per_frame, 10);
  EXPECT_NE(warning.find("steps_per_frame"), std::string::npos) << warning.substr(0, 200);
  EXPECT_LT(warning.size(), 400u);
  fs::remove_all(d);
}

TEST(Settings, SaveCreatesTheFolderAndLeavesNoTemporaryFile) {
  const fs::path d = fresh_dir("save");
  const fs::path f = d / "deeper" / "settings.txt";
  save_gui_settings(unusual(), f.string());
  std::string warning;
  const GuiSettings s = load_gui_settings(f.string(), &warning);
  EXPECT_TRUE(warning.empty()) << warning;
  EXPECT_EQ(s.steps_per_frame, 37);
  int n = 0;
  for (const auto& e : fs::directory_iterator(d / "deeper")) n += e.is_regular_file();
  EXPECT_EQ(n, 1);
  fs::remove_all(d);
}

TEST(Settings, ConfigDirFollowsXdgThenHome) {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  const std::string saved_xdg = xdg ? xdg : "", saved_home = home ? home : "";
  EXPECT_EQ(config_dir("/given"), "/given");
  setenv("XDG_CONFIG_HOME", "/xdg", 1);
  EXPECT_EQ(config_dir(""), "/xdg/dampbound");
  setenv("XDG_CONFIG_HOME", "relative", 1);  // not absolute: ignored (XDG spec)
  setenv("HOME", "/home/u", 1);
  EXPECT_EQ(config_dir(""), "/home/u/.config/dampbound");
  unsetenv("XDG_CONFIG_HOME");
  EXPECT_EQ(config_dir(""), "/home/u/.config/dampbound");
  if (xdg) setenv("XDG_CONFIG_HOME", saved_xdg.c_str(), 1);
  if (home)
    setenv("HOME", saved_home.c_str(), 1);
  else
    unsetenv("HOME");
}

TEST(Settings, ImGuiIniCheck) {
  EXPECT_TRUE(imgui_ini_looks_valid(
      "[Window][Parameters]\nPos=0,0\nSize=384,610\nCollapsed=0\n\n[Window][Mesh view]\n"
      "Pos=384,0\n"));
  EXPECT_TRUE(imgui_ini_looks_valid(""));
  EXPECT_FALSE(imgui_ini_looks_valid("[Window\nPos=0,0\n"));
  EXPECT_FALSE(imgui_ini_looks_valid("random words\n"));
  EXPECT_FALSE(imgui_ini_looks_valid(std::string("[Window][a]\nPos=\x01\x02\n")));
}

}  // namespace
}  // namespace dampbound::ui
