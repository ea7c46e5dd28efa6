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
#include <vector>

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
  EXPECT_EQ(calls, 5);  // the first frame's layout pass, then one call per frame
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

// ImGui lays a tab bar out from the frame before: built once, its first frame shows no tab
// and no tab's contents (a `gui --frames 1` screenshot had no tab bars, and the Status table
// wrapped one letter per line). The layout pass is that frame, built and never drawn.
TEST(GlfwHost, TheFirstFrameIsLaidOutBeforeItIsDrawn) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run -a)";
  WindowOptions opt;
  opt.width = 400;
  opt.height = 300;
  opt.vsync = false;
  opt.visible = false;
  opt.max_frames = 1;
  opt.screenshot_frame = 0;
  GlfwHost host(opt);
  struct Call {
    int index;
    bool layout_pass, tab_bar, tab_open;
    float tab_width;
  };
  std::vector<Call> calls;
  const WindowRun run = host.run([&](FrameInfo& info) {
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(
        ImVec2(static_cast<float>(info.width), static_cast<float>(info.height)));
    ImGui::Begin("tabs");
    Call c{info.index, info.layout_pass, false, false, 0.0f};
    if (ImGui::BeginTabBar("bar")) {
      c.tab_bar = true;
      c.tab_open = ImGui::BeginTabItem("First tab");
      c.tab_width = ImGui::GetItemRectSize().x;
      if (c.tab_open) {
        ImGui::TextUnformatted("contents");
        ImGui::EndTabItem();
      }
      if (ImGui::BeginTabItem("Second tab")) ImGui::EndTabItem();
      ImGui::EndTabBar();
    }
    ImGui::End();
    calls.push_back(c);
  });
  EXPECT_EQ(run.frames, 1);
  ASSERT_EQ(calls.size(), 2u);
  EXPECT_EQ(calls[0].index, 0);
  EXPECT_TRUE(calls[0].layout_pass);
  EXPECT_EQ(calls[1].index, 0);
  EXPECT_FALSE(calls[1].layout_pass);
  // The drawn frame has its tab: open, as wide as its label.
  EXPECT_TRUE(calls[1].tab_bar);
  EXPECT_TRUE(calls[1].tab_open);
  EXPECT_GT(calls[1].tab_width, ImGui::CalcTextSize("First tab").x);
  std::printf("layout pass: tab open %d, width %.1f; drawn frame: tab open %d, width %.1f\n",
              calls[0].tab_open, calls[0].tab_width, calls[1].tab_open, calls[1].tab_width);
  ASSERT_TRUE(run.screenshot.has_value());
  EXPECT_FALSE(is_blank(*run.screenshot));
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
