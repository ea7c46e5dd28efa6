// Headless rendering through the EGL host (Mesa surfaceless on CI): the plot lands where the
// data<->pixel map says, PNGs are written, errors are exceptions. Sample PNGs go to
// $DAMPBOUND_UI_PNG_DIR, else ui_test_output/ in the working directory.
#if defined(DAMPBOUND_HAVE_EGL)
#include "ui/egl_host.hpp"
#include "ui/figure.hpp"
#include "ui/image.hpp"
#include "ui/plot.hpp"

#include <gtest/gtest.h>
#include <imgui.h>

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

std::string out_path(const std::string& name) {
  const char* env = std::getenv("DAMPBOUND_UI_PNG_DIR");
  const std::filesystem::path dir = env != nullptr && *env != '\0' ? env : "ui_test_output";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

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

const ImU32 kRed = IM_COL32(220, 20, 30, 255);

PlotSpec line_spec() {
  PlotSpec spec;
  spec.title = "y = x";
  spec.x.label = "x (cm)";
  spec.y.label = "y (cm)";
  PlotSeries s;
  s.label = "y = x";
  s.color = kRed;
  s.thickness = 3.0f;
  for (int i = 0; i <= 100; ++i) {
    s.x.push_back(i * 0.1);
    s.y.push_back(i * 0.1);
  }
  spec.series.push_back(s);
  PlotRefLine h;
  h.label = "threshold";
  h.at = 8.0;
  h.color = IM_COL32(90, 90, 90, 255);
  spec.ref_lines.push_back(h);
  return spec;
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
  const RenderStats& st = host().last_stats();
  std::printf("1200x700 line plot: first frame %.1f ms, then %.1f ms/frame, readback %.1f ms\n",
              st.first_frame_ms, st.mean_frame_ms, st.readback_ms);
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

TEST(EglRender, BandTracesAndTiming) {
  const int w = 1200, h = 700;
  PlotSpec spec;
  spec.title = "Damping bounds of the watched node";
  spec.x.label = "iteration";
  spec.y.label = "damping γ";
  spec.y.log = true;
  PlotBand band;
  band.label = "feasible damping";
  PlotSeries lo, hi, trace;
  lo.label = "lower bound 2√(mκ) (eq. 5)";
  lo.color = palette_color(0);
  hi.label = "upper bound (eq. 6)";
  hi.color = palette_color(3);
  const int n = 10000;
  for (int i = 0; i < n; ++i) {
    const double t = i;
    band.x.push_back(t);
    band.y_lo.push_back(2e-3);
    const double up = 1e-3 + 0.05 * std::exp(-t / 3000.0) * (1.0 + 0.9 * std::sin(t * 0.05));
    band.y_hi.push_back(i % 1000 == 0 ? std::numeric_limits<double>::infinity() : up);
  }
  lo.x = hi.x = band.x;
  lo.y = band.y_lo;
  hi.y = band.y_hi;
  spec.bands.push_back(band);
  spec.series = {lo, hi};
  PlotRefLine user;
  user.label = "user γ";
  user.at = 4e-3;
  spec.ref_lines.push_back(user);
  const Image img = host().render_frames(w, h, plot_frame(spec), 5);
  EXPECT_FALSE(is_blank(img));
  const RenderStats& st = host().last_stats();
  std::printf("1200x700 band + two 10000-point traces: first frame %.1f ms, then %.1f ms/frame\n",
              st.first_frame_ms, st.mean_frame_ms);
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
