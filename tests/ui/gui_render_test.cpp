// The whole tuner window rendered headless through the EGL host (Mesa surfaceless on CI): the
// same frame function as the GLFW window, the mesh view's offscreen GL pass included, and the
// export of the plots from inside a frame. PNGs go to $DAMPBOUND_UI_PNG_DIR, else
// ui_test_output/.
#if defined(DAMPBOUND_HAVE_EGL)
#include "ui/egl_host.hpp"
#include "ui/gui_app.hpp"
#include "ui/gui_export.hpp"
#include "ui/image.hpp"
#include "ui/mesh_style.hpp"
#include "ui/tuner_plots.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "core/scene.hpp"

namespace dampbound::ui {
namespace {

namespace fs = std::filesystem;

std::string out_path(const std::string& name) {
  const char* env = std::getenv("DAMPBOUND_UI_PNG_DIR");
  const fs::path dir = env != nullptr && *env != '\0' ? env : "ui_test_output";
  fs::create_directories(dir);
  return (dir / name).string();
}

GuiOptions options(const fs::path& config) {
  GuiOptions o;
  o.config_dir = config.string();
  o.scenes_dir = DAMPBOUND_SOURCE_DIR "/scenes";
  o.scene = load_scene(DAMPBOUND_SOURCE_DIR "/scenes/paper-plane.toml");
  o.steps_per_frame = 4;
  o.play = true;
  o.demo = true;
  o.scripted = true;
  return o;
}

TEST(GuiRender, WholeWindowHeadless) {
  const fs::path config = fs::temp_directory_path() / "dampbound_gui_render_test";
  fs::remove_all(config);
  EglOptions eo;
  eo.render = gui_render_options();
  EglHost host(eo);
  GuiApp app(options(config));
  ASSERT_EQ(app.tuner().pins().size(), 2u);
  const int frames = 3;
  std::string export_summary;
  const Image img = host.render_frames(1280, 800, [&](FrameInfo& info) {
    app.frame(info);
    if (info.index == frames - 1) {
      // Export from inside a frame, as the button does.
      Tuner& t = app.tuner();
      export_summary = export_runs(t, {tuner_displacement_plot(t, {}), tuner_envelope_plot(t, {})},
                                   (config / "export").string(), "test");
    }
  }, frames);
  EXPECT_EQ(app.tuner().session().state().iteration, frames * 4);
  EXPECT_FALSE(is_blank(img));
  // The mesh view drew its nodes: many pixels of the "within bounds" colour.
  EXPECT_GT(count_color(img, rgba_from_u32(status_color(NodeStatus::within)), 10), 200);
  // The pinned runs' colours are on the plots.
  for (const Pin& p : app.tuner().pins()) EXPECT_GT(count_color(img, rgba_from_u32(p.color), 12), 20);
  write_png_atomic(img, out_path("gui_window.png"));
  // The export wrote a readable, non-blank figure and the CSVs.
  EXPECT_NE(export_summary.find("test_plots.png"), std::string::npos);
  const Image fig = read_png((config / "export" / "test_plots.png").string());
  EXPECT_EQ(fig.width, 1400);
  EXPECT_EQ(fig.height, 1000);
  EXPECT_FALSE(is_blank(fig));
  EXPECT_EQ(fig.pixel(2, 2), (Rgba{255, 255, 255, 255}));  // a light figure
  EXPECT_GT(count_color(fig, rgba_from_u32(app.tuner().pins()[0].color), 12), 50);
  EXPECT_TRUE(fs::exists(config / "export" / "test_traces.csv"));
  EXPECT_TRUE(fs::exists(config / "export" / "test_runs.csv"));
  // Settings and layout are saved into the config folder.
  app.save();
  app.release_gl();
  EXPECT_TRUE(fs::exists(config / "settings.txt"));
  fs::remove_all(config);
}

TEST(GuiRender, DivergedRunShowsNoNaNAndStops) {
  EglOptions eo;
  eo.render = gui_render_options();
  EglHost host(eo);
  GuiOptions o = options(fs::path());
  o.config_dir.clear();
  o.demo = false;
  o.overrides = [](Params& p, StopRules&) {
    p.kappa = 1.0;
    p.gamma = 0.0;
  };
  GuiApp app(o);
  const Image img = host.render_frames(1024, 640, app.frame_fn(), 4);
  EXPECT_EQ(app.tuner().session().result().outcome, Outcome::diverged);
  EXPECT_FALSE(app.tuner().playing());
  EXPECT_FALSE(is_blank(img));
  write_png_atomic(img, out_path("gui_diverged.png"));
  app.release_gl();
}

}  // namespace
}  // namespace dampbound::ui
#endif
