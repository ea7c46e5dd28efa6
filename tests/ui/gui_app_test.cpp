// The tuner window's state is the model's: after a scene switch no panel shows (or applies)
// the last scene's answers; a settings file that cannot be read is left as it is.
#if defined(DAMPBOUND_HAVE_EGL)
#include "ui/gui_app.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/scene_file.hpp"
#include "ui/egl_host.hpp"
#include "tests/ui/ui_test_util.hpp"

namespace dampbound::ui {
namespace {

using ui_test::headless;

namespace fs = std::filesystem;

GuiOptions options(const fs::path& config) {
  GuiOptions o;
  o.config_dir = config.string();
  o.scenes_dir = DAMPBOUND_SOURCE_DIR "/scenes";
  o.scene = load_scene(DAMPBOUND_SOURCE_DIR "/scenes/two-node.toml");
  o.play = false;
  o.demo = false;
  o.scripted = true;
  return o;
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(GuiApp, ASceneSwitchDropsTheLastScenesSuggestions) {
  GuiOptions o = options(fs::path());
  o.config_dir.clear();
  EglHost host(headless());
  GuiApp app(o);
  bool had = false, after = true;
  host.render_frames(
      1024, 640,
      [&](FrameInfo& info) {
        if (info.layout_pass) return app.frame(info);
        if (info.index == 0) {
          app.start_suggest();
          app.suggestions().wait();
          app.start_substeps();
          app.substeps().wait();
        }
        app.frame(info);
        if (info.index == 0) {
          had = app.suggestions().result().has_value() && app.substeps().result().has_value();
          app.open_scene(DAMPBOUND_SOURCE_DIR "/scenes/paper-plane.toml");
        }
        if (info.index == 1)
          after = app.suggestions().result().has_value() || app.substeps().result().has_value();
      },
      2);
  EXPECT_TRUE(had);
  EXPECT_FALSE(after) << "the last scene's suggestions are still on show";
  EXPECT_EQ(app.tuner().scene().name, "paper-plane");
  app.release_gl();
}

// The stiffness ceiling and the Rayleigh pair speak for the model they were computed for: the
// frame after a parameter change (their own apply button's) or a Reset shows neither, and
// their apply buttons are gone with them.
TEST(GuiApp, AParameterChangeOrAResetDropsTheCeilingAndThePair) {
  GuiOptions o = options(fs::path());
  o.config_dir.clear();
  EglHost host(headless());
  GuiApp app(o);
  std::vector<bool> shown;
  host.render_frames(
      1024, 640,
      [&](FrameInfo& info) {
        if (info.layout_pass) return app.frame(info);
        if (info.index == 0 || info.index == 2) {
          app.start_knobs();
          app.knobs().wait();
        }
        app.frame(info);
        shown.push_back(app.knobs().result().has_value());
        if (info.index == 0) {
          ASSERT_TRUE(app.knobs().result().has_value()) << app.knobs().error();
          const auto p = with_kappa_ceiling(app.tuner().params(), *app.knobs().result());
          ASSERT_TRUE(p.has_value());
          app.tuner().set_params(*p);  // what "apply kappa" does
        }
        if (info.index == 2) app.tuner().reset();
      },
      4);
  EXPECT_EQ(shown, (std::vector<bool>{true, false, true, false}));
  app.release_gl();
}

TEST(GuiApp, ACorruptSettingsFileIsLeftAsItIs) {
  const fs::path config = fs::temp_directory_path() / "dampbound_gui_app_corrupt_settings";
  fs::remove_all(config);
  fs::create_directories(config);
  const std::string bad = "dampbound-gui-settings 1\nm = 0.001\ngamma = -1\nlog_y = true\n";
  std::ofstream(config / "settings.txt", std::ios::binary) << bad;
  {
    GuiApp app(options(config));
    app.save();
  }
  EXPECT_EQ(text_of(config / "settings.txt"), bad);
}

}  // namespace
}  // namespace dampbound::ui
#endif
