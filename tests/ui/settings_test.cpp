// What the tuner remembers (ui/settings.hpp): exact round trip, corrupt files ignored with a
// one-line warning, the config folder, atomic saves.
#include "ui/settings.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

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
  EXPECT_FALSE(back->show_springs);
  EXPECT_TRUE(back->show_anchors);
  EXPECT_EQ(back->point_size, 9.5f);
  EXPECT_EQ(back->export_dir, "/tmp/out dir");
  EXPECT_EQ(back->export_prefix, "fig1_like");
  EXPECT_EQ(back->window_width, 1280);
  EXPECT_EQ(back->window_height, 800);
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
