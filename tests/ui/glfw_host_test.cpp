// The window host under a real X display (CI: xvfb-run -a). Skipped without DISPLAY; without
// a display the host must refuse with an exception, never crash.
#if defined(DAMPBOUND_HAVE_GLFW)
#include "ui/glfw_host.hpp"
#include "ui/image.hpp"
#include "ui/plot.hpp"

#include <gtest/gtest.h>
#include <imgui.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace dampbound::ui {
namespace {

bool have_display() {
  const char* d = std::getenv("DISPLAY");
  return d != nullptr && *d != '\0';
}

TEST(GlfwHost, RendersAWindowAndTakesAScreenshot) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run -a)";
  WindowOptions opt;
  opt.width = 640;
  opt.height = 400;
  opt.vsync = false;
  opt.max_frames = 4;
  opt.screenshot_frame = 2;
  GlfwHost host(opt);
  PlotSpec spec;
  spec.title = "window host";
  PlotSeries s;
  s.label = "y = x^2";
  for (int i = 0; i <= 50; ++i) {
    s.x.push_back(i);
    s.y.push_back(i * i);
  }
  spec.series.push_back(s);
  int calls = 0;
  const WindowRun run = host.run([&](FrameInfo& info) {
    ++calls;
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(info.width), static_cast<float>(info.height)));
    ImGui::Begin("plot");
    plot_widget("p", spec);
    ImGui::End();
  });
  EXPECT_EQ(run.frames, 4);
  EXPECT_EQ(calls, 4);
  ASSERT_TRUE(run.screenshot.has_value());
  EXPECT_GE(run.screenshot->width, 640);
  EXPECT_GE(run.screenshot->height, 400);
  EXPECT_FALSE(is_blank(*run.screenshot));
  const char* env = std::getenv("DAMPBOUND_UI_PNG_DIR");
  const std::filesystem::path dir = env != nullptr && *env != '\0' ? env : "ui_test_output";
  std::filesystem::create_directories(dir);
  write_png_atomic(*run.screenshot, (dir / "glfw_window.png").string());
  std::printf("GLFW renderer: %s, %.2f ms/frame\n", host.gl_renderer().c_str(), run.mean_frame_ms);
}

TEST(GlfwHost, FrameFunctionCanCloseTheWindow) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run -a)";
  WindowOptions opt;
  opt.width = 200;
  opt.height = 100;
  opt.vsync = false;
  opt.visible = false;
  GlfwHost host(opt);
  const WindowRun run = host.run([](FrameInfo& info) { info.close = info.index == 2; });
  EXPECT_EQ(run.frames, 3);
}

TEST(GlfwHost, NoDisplayIsAnException) {
  if (have_display()) GTEST_SKIP() << "a display is available";
  try {
    GlfwHost host;
    FAIL() << "a window opened without a display";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("GLFW: ", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace dampbound::ui
#endif  // DAMPBOUND_HAVE_GLFW
