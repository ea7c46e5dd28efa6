// Headless rendering through the EGL host (Mesa surfaceless on CI): the plot lands where the
// data<->pixel map says, PNGs are written, errors are exceptions. Sample PNGs go to
// $DAMPBOUND_UI_PNG_DIR, else ui_test_output/ in the working directory.
#if defined(DAMPBOUND_HAVE_EGL)
#include "tests/ui/plot_specs.hpp"
#include "ui/egl_host.hpp"
#include "ui/figure.hpp"
#include "ui/image.hpp"
#include "ui/plot.hpp"
#include "tests/ui/ui_test_util.hpp"

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

namespace dampbound::ui {
namespace {

using ui_test::out_path;

/// One host for the whole suite: making the context is the slow part.
EglHost& host() {
  static std::unique_ptr<EglHost> h = [] {
    auto p = std::make_unique<EglHost>();
    std::printf("EGL platform: %s, renderer: %s, version: %s\n", p->platform_name().c_str(),
                p->gl_renderer().c_str(), p->gl_version().c_str());
    return p;
  }();
  return *h;
}

TEST(EglRender, LineLandsWhereTheTransformSays) {
  const int w = 1200, h = 700;
  const PlotSpec spec = line_spec();
  PlotLayout lay;
  const Image img = host().render_frames(w, h, [&](FrameInfo&) {
    lay = draw_plot(ImGui::GetBackgroundDrawList(), ImVec2(0, 0), ImVec2(w, h), spec,
                    plot_style_light());
  });
  ASSERT_EQ(img.width, w);
  ASSERT_EQ(img.height, h);
  EXPECT_FALSE(is_blank(img));
  const Rgba red = rgba_from_u32(kRed);
  for (double v : {2.0, 5.0, 7.5}) {
    const int px = static_cast<int>(std::lround(lay.x.to_px(v)));
    const int py = static_cast<int>(std::lround(lay.y.to_px(v)));
    EXPECT_TRUE(has_color_near(img, px, py, 2, red, 12)) << "data (" << v << ", " << v << ") at pixel " << px << "," << py;
  }
  // Off the line: no red at (x, y) = (2, 7).
  EXPECT_FALSE(has_color_near(img, static_cast<int>(std::lround(lay.x.to_px(2.0))),
                              static_cast<int>(std::lround(lay.y.to_px(7.0))), 3, red, 12));
  const std::string path = out_path("egl_line.png");
  write_png_atomic(img, path);
  const Image back = read_png(path);
  EXPECT_EQ(back.width, w);
  EXPECT_EQ(back.height, h);
  EXPECT_EQ(back.rgba, img.rgba);
}

TEST(EglRender, HeatmapBandsLogAxesLegend) {
  const int w = 1200, h = 700;
  PlotSpec spec;
  spec.title = "Stability map (synthetic)";
  spec.x.label = "mass m";
  spec.y.label = "stiffness κ";
  spec.x.log = spec.y.log = true;
  spec.legend = LegendPos::Outside;
  const int n = 60;
  for (int i = 0; i <= n; ++i) {
    spec.heatmap.x_edges.push_back(1e-4 * std::pow(1000.0, i / double(n)));
    spec.heatmap.y_edges.push_back(1e-4 * std::pow(1000.0, i / double(n)));
  }
  const ImU32 kBlue = IM_COL32(40, 90, 200, 255), kGrey = IM_COL32(200, 200, 200, 255),
              kOrange = IM_COL32(240, 140, 30, 255);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      spec.heatmap.cell_color.push_back(j > i + 10 ? kOrange : j > i - 5 ? kGrey : kBlue);
    }
  }
  spec.heatmap.legend = {{"restored", kBlue}, {"not restored", kGrey}, {"diverged", kOrange}};
  PlotSeries boundary;
  boundary.label = "predicted boundary";
  boundary.color = IM_COL32(0, 0, 0, 255);
  boundary.dashed = true;
  boundary.x = {1e-4, 1e-1};
  boundary.y = {1e-4 * std::pow(1000.0, 10.0 / n), 1e-1 * std::pow(1000.0, 10.0 / n)};
  spec.series.push_back(boundary);
  PlotLayout lay;
  const Image img = host().render_frames(w, h, [&](FrameInfo&) {
    lay = draw_plot(ImGui::GetBackgroundDrawList(), ImVec2(0, 0), ImVec2(w, h), spec,
                    plot_style_light());
  });
  // The centre of cell (5, 40) is diverged (orange), of (40, 5) restored (blue).
  auto centre = [&](int i, int j) {
    const double x = std::sqrt(spec.heatmap.x_edges[i] * spec.heatmap.x_edges[i + 1]);
    const double y = std::sqrt(spec.heatmap.y_edges[j] * spec.heatmap.y_edges[j + 1]);
    return std::pair<int, int>(static_cast<int>(lay.x.to_px(x)), static_cast<int>(lay.y.to_px(y)));
  };
  auto [ox, oy] = centre(5, 40);
  EXPECT_TRUE(has_color_near(img, ox, oy, 0, rgba_from_u32(kOrange), 2));
  auto [bx, by] = centre(40, 5);
  EXPECT_TRUE(has_color_near(img, bx, by, 0, rgba_from_u32(kBlue), 2));
  write_png_atomic(img, out_path("egl_heatmap.png"));
}

TEST(EglRender, BandTracesAndLines) {
  const int w = 1200, h = 700;
  const PlotSpec spec = band_spec();
  PlotLayout lay;
  const Image img = host().render_frames(w, h, [&](FrameInfo&) {
    lay = draw_plot(ImGui::GetBackgroundDrawList(), ImVec2(0, 0), ImVec2(w, h), spec,
                    plot_style_light());
  });
  auto px = [&](double t, double gamma) {
    return std::pair<int, int>(static_cast<int>(std::lround(lay.x.to_px(t))),
                               static_cast<int>(std::lround(lay.y.to_px(gamma))));
  };
  // The lower bound (eq. 5) at 2e-3 and the upper bound where the sample says, in their
  // colours, at iterations away from the breaks (every 1000th upper sample is +inf).
  for (double t : {1500.0, 2500.0, 3500.0}) {
    SCOPED_TRACE("iteration " + std::to_string(t));
    const auto [lx, ly] = px(t, 2e-3);
    EXPECT_TRUE(has_color_near(img, lx, ly, 2, rgba_from_u32(palette_color(0)), 16));
    const auto [ux, uy] = px(t, band_upper(static_cast<int>(t)));
    EXPECT_TRUE(has_color_near(img, ux, uy, 3, rgba_from_u32(palette_color(3)), 16));
  }
  // The user's gamma: a dashed grey line at 4e-3 across the plot, darker than the band it
  // crosses: its dashes cover a good part of its row, and a few rows off it nothing does.
  auto luma = [](Rgba c) { return (c.r + c.g + c.b) / 3; };
  auto dark_columns = [&](int row) {
    int n = 0;
    for (int x = static_cast<int>(lay.area.x0) + 2; x < static_cast<int>(lay.area.x1) - 2; ++x)
      n += luma(img.pixel(x, row)) + 40 < luma(img.pixel(x, row - 4));
    return n;
  };
  const int user_row = px(0, 4e-3).second;
  const int width = static_cast<int>(lay.area.x1 - lay.area.x0);
  EXPECT_GT(std::max(dark_columns(user_row), dark_columns(user_row + 1)), width / 4);
  EXPECT_LT(dark_columns(user_row - 8), width / 10);
  // The feasible band is shaded (greenish) between the bounds; above it, late on, the plot
  // area is its plain background.
  const auto [ix, iy] = px(300, 1.5e-2);
  const Rgba in = img.pixel(ix, iy);
  EXPECT_GT(in.g, in.r + 20);
  EXPECT_GT(in.g, in.b + 20);
  const auto [ox, oy] = px(9350, 2.5e-2);
  EXPECT_EQ(img.pixel(ox, oy), rgba_from_u32(plot_style_light().plot_background));
  write_png_atomic(img, out_path("egl_band.png"));
}

TEST(EglRender, GuiWindowWithPlotWidget) {
  EglOptions opt;
  opt.render = gui_render_options();
  EglHost dark(opt);
  const PlotSpec spec = line_spec();
  const Image img = dark.render_frames(1280, 800, [&](FrameInfo& info) {
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(info.width), static_cast<float>(info.height)));
    ImGui::Begin("dampbound", nullptr, ImGuiWindowFlags_NoCollapse);
    static float gamma = 0.002f;
    ImGui::SliderFloat("gamma", &gamma, 0.0f, 0.01f, "%.4f");
    ImGui::Text("Renderer: %s", dark.gl_renderer().c_str());
    plot_widget("plot", spec, ImVec2(-1, -1));
    ImGui::End();
  });
  EXPECT_FALSE(is_blank(img));
  write_png_atomic(img, out_path("egl_gui_window.png"));
}

TEST(EglRender, HoverDrawsCrosshair) {
  const int w = 800, h = 500;
  const PlotSpec spec = line_spec();
  auto render_with_mouse = [&](ImVec2 mouse) {
    PlotLayout lay;
    Image img = host().render_frames(w, h, [&](FrameInfo& info) {
      ImGui::GetIO().MousePos = mouse;  // seen by the next NewFrame
      ImGui::SetNextWindowPos(ImVec2(0, 0));
      ImGui::SetNextWindowSize(ImVec2(static_cast<float>(info.width), static_cast<float>(info.height)));
      ImGui::Begin("hover", nullptr, ImGuiWindowFlags_NoDecoration);
      lay = plot_widget("plot", spec, ImVec2(-1, -1));
      ImGui::End();
    }, 3);
    return std::make_pair(img, lay);
  };
  const auto [away, lay] = render_with_mouse(ImVec2(-100, -100));
  const ImVec2 m(static_cast<float>(std::floor(lay.x.to_px(3.3))), static_cast<float>(std::floor(lay.y.to_px(6.1))));
  const auto [over, lay2] = render_with_mouse(m);
  // The vertical crosshair changes the column under the mouse, far below the mouse.
  const int x = static_cast<int>(m.x), y = static_cast<int>(lay.area.y1) - 5;
  EXPECT_NE(away.pixel(x, y), over.pixel(x, y));
  EXPECT_EQ(away.pixel(x + 40, y), over.pixel(x + 40, y));
  write_png_atomic(over, out_path("egl_hover.png"));
}

TEST(EglRender, ThrowingFrameFunctionLeavesTheHostUsable) {
  EXPECT_THROW(host().render_frames(100, 100, [](FrameInfo&) { throw std::runtime_error("boom"); }),
               std::runtime_error);
  const Image img = host().render_frames(120, 80, plot_frame(line_spec()), 1);
  EXPECT_EQ(img.width, 120);
  EXPECT_FALSE(is_blank(img));
}

TEST(EglRender, MissingFontFallsBackToTheBuiltInOne) {
  EglOptions opt;
  opt.render.fonts.ttf_path = "/nonexistent/font.ttf";
  opt.render.fonts.title_ttf_path = "/nonexistent/bold.ttf";
  EglHost h(opt);
  const Image img = h.render_frames(600, 400, plot_frame(line_spec()), 1);
  EXPECT_FALSE(is_blank(img));
  write_png_atomic(img, out_path("egl_builtin_font.png"));
}

TEST(EglRender, BadSizeThrows) {
  EXPECT_THROW(host().render_frames(0, 10, [](FrameInfo&) {}), std::runtime_error);
  EXPECT_THROW(host().render_frames(10, 100000, [](FrameInfo&) {}), std::runtime_error);
}

TEST(EglRender, ForcedDevicePlatformWorksOrThrowsOneLine) {
  EglOptions opt;
  opt.platform = EglPlatform::Device;
  try {
    EglHost dev(opt);
    const Image img = dev.render_frames(64, 48, plot_frame(line_spec()), 1);
    EXPECT_FALSE(is_blank(img));
    std::printf("device platform: %s (%s)\n", dev.platform_name().c_str(), dev.gl_renderer().c_str());
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("EGL: ", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    std::printf("device platform unavailable: %s\n", msg.c_str());
  }
  EXPECT_THROW(parse_egl_platform("wayland"), std::runtime_error);
}

}  // namespace
}  // namespace dampbound::ui
#endif  // DAMPBOUND_HAVE_EGL
