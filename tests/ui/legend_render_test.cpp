// Nothing hides the data: for each figure and each tuner plot at the sizes the tuner window
// gives it, the plot is rendered twice with the legend left out, once with the curves (series
// and reference lines) and once without, and the pixels that differ inside the box the legend
// is drawn in are counted: curve pixels a legend would hide. Every count must be zero.
#if defined(DAMPBOUND_HAVE_EGL)
#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/analysis/figures.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/physics/bounds.hpp"
#include "ui/egl_host.hpp"
#include "ui/gui_layout.hpp"
#include "ui/gui_widgets.hpp"
#include "ui/image.hpp"
#include "ui/plot.hpp"
#include "ui/trace_plots.hpp"
#include "ui/tuner.hpp"
#include "ui/tuner_plots.hpp"

namespace dampbound::ui {
namespace {

SceneSpec scene(const std::string& name) {
  return load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/" + name + ".toml");
}

/// Curve pixels under the legend box of `spec` drawn w x h with `style` on `host`.
size_t hidden_curve_pixels(EglHost& host, const PlotSpec& spec, int w, int h, PlotStyle style,
                           const std::string& what) {
  PlotLayout lay;
  auto render = [&](bool curves) {
    return host.render_frames(w, h, [&](FrameInfo&) {
      PlotStyle s = style;
      if (s.background == 0) s.background = IM_COL32(30, 30, 34, 255);  // the window's colour
      s.draw_legend = false;
      s.draw_curves = curves;
      lay = draw_plot(ImGui::GetBackgroundDrawList(), ImVec2(0, 0),
                      ImVec2(static_cast<float>(w), static_cast<float>(h)), spec, s);
    }, 1);
  };
  const Image with = render(true), without = render(false);
  EXPECT_NE(lay.legend_pos, LegendPos::Hidden) << what << ": no legend";
  size_t n = 0;
  const PixelRect& b = lay.legend;
  for (int y = std::max(0, static_cast<int>(std::floor(b.y0))); y < std::min(h, static_cast<int>(std::ceil(b.y1))); ++y)
    for (int x = std::max(0, static_cast<int>(std::floor(b.x0))); x < std::min(w, static_cast<int>(std::ceil(b.x1))); ++x)
      if (with.pixel(x, y) != without.pixel(x, y)) ++n;
  std::printf("%-58s legend %-6s at (%4.0f,%4.0f)-(%4.0f,%4.0f): %zu curve pixels under it\n",
              what.c_str(),
              lay.legend_pos == LegendPos::Outside ? "right" :
              lay.legend_pos == LegendPos::Above ? "above" : "corner",
              b.x0, b.y0, b.x1, b.y1, n);
  return n;
}

TEST(LegendRender, NoFigureLegendHidesACurve) {
  EglHost host;
  const SceneSpec plane = scene("paper-plane");
  const std::vector<std::pair<std::string, FigureData>> figures = {
      {"fig1", figure_fig1(plane)},
      {"fig2", figure_fig2(plane)},
      {"paper-plane-cut", figure_scene(scene("paper-plane-cut"))},
      {"paper-plane", figure_scene(plane)}};
  for (const auto& [name, fig] : figures) {
    const PlotSpec spec = figure_plot(fig);
    for (const auto& [w, h] : std::vector<std::pair<int, int>>{{1200, 700}, {1024, 640}, {640, 400}})
      EXPECT_EQ(hidden_curve_pixels(host, spec, w, h, plot_style_light(),
                                    "figure " + name + " " + std::to_string(w) + "x" +
                                        std::to_string(h)),
                0u);
  }
}

/// The tuner's two plots at the size the window's default layout gives their panels (less
/// the panel's title bar, padding and toolbar), after `steps` steps.
void check_tuner(EglHost& host, Tuner& t, float W, float H, const std::string& what) {
  for (const PanelRect& r : default_layout(W, H)) {
    if (r.name != "Damping bounds" && r.name != "Displacement") continue;
    const int w = static_cast<int>(r.w) - 16, h = static_cast<int>(r.h) - 62;
    TunerPlotOptions o;
    const PlotSpec spec = r.name == "Displacement" ? tuner_displacement_plot(t, o)
                                                   : tuner_envelope_plot(t, o);
    EXPECT_EQ(hidden_curve_pixels(host, spec, w, h, gui_plot_style(),
                                  what + " " + r.name + " " + std::to_string(w) + "x" +
                                      std::to_string(h)),
              0u);
  }
}

void pin_demo(Tuner& t) {  // as gui --demo: gamma at a quarter of the lower bound and at it
  const Params base = t.params();
  const double lo = lower_bound(base.m, base.kappa);
  for (double g : {lo / 4, lo}) {
    Params p = base;
    p.gamma = g;
    p.policy = DampingPolicy::fixed;
    t.set_params(p);
    t.reset();
    t.step(t.session().rules().max_iterations);
    t.pin("gamma = " + std::to_string(g));
  }
  t.set_params(base);
  t.reset();
}

TEST(LegendRender, NoTunerLegendHidesACurve) {
  EglOptions opt;
  opt.render = gui_render_options();
  EglHost host(opt);
  {
    Tuner t(scene("paper-plane"));
    t.step(200);
    check_tuner(host, t, 1024, 640, "tuner paper-plane 1024x640");
    check_tuner(host, t, 1280, 800, "tuner paper-plane 1280x800");
    pin_demo(t);
    t.step(200);
    check_tuner(host, t, 1280, 800, "tuner paper-plane pins 1280x800");
    check_tuner(host, t, 1600, 1000, "tuner paper-plane pins 1600x1000");
    check_tuner(host, t, 1024, 640, "tuner paper-plane pins 1024x640");
  }
  {
    Tuner t(scene("paper-plane-cut"));
    t.step(300);
    check_tuner(host, t, 1600, 1000, "tuner paper-plane-cut 1600x1000");
    check_tuner(host, t, 1024, 640, "tuner paper-plane-cut 1024x640");
  }
}

}  // namespace
}  // namespace dampbound::ui
#endif
