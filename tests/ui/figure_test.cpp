// The paper's figures rendered headless (EGL, no display): the PNG has the requested size, is
// not blank, and each curve's pixels are where its CSV data says, at sampled points.
#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/analysis/figures.hpp"
#include "core/io/scene_file.hpp"
#include "ui/egl_host.hpp"
#include "ui/image.hpp"
#include "ui/plot.hpp"
#include "ui/render_png.hpp"
#include "ui/trace_plots.hpp"

namespace dampbound::ui {
namespace {

const SceneSpec& plane() {
  static const SceneSpec s =
      load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/paper-plane.toml");
  return s;
}

/// CSV rows of one run: iteration -> displacement, read back from write_figure_csv.
std::map<std::string, std::map<int, double>> read_csv(const std::string& text) {
  std::map<std::string, std::map<int, double>> rows;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("run,iteration,time,displacement,", 0), 0u) << line;
  while (std::getline(in, line)) {
    std::istringstream f(line);
    std::string run, it, t, d;
    std::getline(f, run, ',');
    std::getline(f, it, ',');
    std::getline(f, t, ',');
    std::getline(f, d, ',');
    rows[run][std::stoi(it)] = std::stod(d);
  }
  return rows;
}

/// Renders the figure as `dampbound figure` does, then checks sampled CSV points.
void check_figure(const FigureData& fig, const std::string& name,
                  const std::vector<std::pair<int, std::vector<int>>>& samples) {
  const int w = 1200, h = 700;
  const PlotSpec spec = figure_plot(fig);
  const std::string png = name + ".png";
  render_plots_png({spec}, 1, w, h, png);
  const Image img = read_png(png);
  ASSERT_EQ(img.width, w);
  ASSERT_EQ(img.height, h);
  ASSERT_FALSE(is_blank(img));

  std::ostringstream csv;
  write_figure_csv(csv, fig);
  const auto rows = read_csv(csv.str());
  ASSERT_EQ(rows.size(), fig.runs.size());

  // The same layout as the figure: one plot filling the display from (0, 0).
  PlotLayout lay;
  EglHost host;
  host.render_frames(w, h, [&](FrameInfo&) {
    lay = layout_plot(ImVec2(0, 0), ImVec2(static_cast<float>(w), static_cast<float>(h)), spec,
                      plot_style_light());
  });
  for (const auto& [run_index, iterations] : samples) {
    const FigureRun& run = fig.runs[static_cast<size_t>(run_index)];
    const Rgba color = rgba_from_u32(palette_color(run_index));
    const auto& data = rows.at(run.label);
    for (int it : iterations) {
      const double y = data.at(it);
      const int px = static_cast<int>(std::lround(lay.x.to_px(it)));
      const int py = static_cast<int>(std::lround(lay.y.to_px(y)));
      EXPECT_TRUE(has_color_near(img, px, py, 2, color, 40))
          << name << " run '" << run.label << "' iteration " << it << " y=" << y << " pixel ("
          << px << ", " << py << ")";
    }
  }
  // Far from every curve (top middle of the plot area, above all data): background only.
  for (int k = 0; k < static_cast<int>(fig.runs.size()); ++k)
    EXPECT_FALSE(has_color_near(img, static_cast<int>(lay.x.to_px(60)),
                                static_cast<int>(lay.y.to_px(fig.log_y ? 4.9 : 4.9)), 3,
                                rgba_from_u32(palette_color(k)), 40))
        << "stray colour of run " << k;
}

TEST(Figure, Fig1CurvesWhereTheCsvSays) {
  const FigureData fig = figure_fig1(plane());
  ASSERT_EQ(fig.runs.size(), 3u);
  // Iteration 25 is near each run's second peak (distinct heights); past iteration 112 only
  // the gamma = 0.0005 run goes on.
  const int last = fig.runs[0].result.iterations;
  check_figure(fig, "fig1_test", {{0, {25, 130, last - 5}}, {1, {25}}, {2, {25, 5}}});
}

TEST(Figure, Fig2CurvesWhereTheCsvSays) {
  const FigureData fig = figure_fig2(plane());
  ASSERT_EQ(fig.runs.size(), 2u);
  EXPECT_TRUE(fig.log_y);
  check_figure(fig, "fig2_test", {{0, {40, fig.runs[0].result.iterations - 2}}, {1, {30}}});
}

TEST(Figure, ReadableLabels) {
  const PlotSpec spec = figure_plot(figure_fig1(plane()));
  EXPECT_NE(spec.title.find("Fig. 1"), std::string::npos);
  EXPECT_EQ(spec.x.label, "iteration");
  EXPECT_NE(spec.y.label.find("(cm)"), std::string::npos);
  ASSERT_EQ(spec.series.size(), 3u);
  EXPECT_NE(spec.series[0].label.find("gamma = 0.0005"), std::string::npos);
  ASSERT_EQ(spec.ref_lines.size(), 1u);
  EXPECT_EQ(spec.ref_lines[0].axis, LineAxis::y);
  EXPECT_DOUBLE_EQ(spec.ref_lines[0].at, 0.05);
}

/// Rows [first, last] of dark (text) pixels in rows [0, below) of `img`, and how many of them
/// lie within 2 pixels of the left or right edge (a title cut off there).
struct TitleInk {
  int first = -1, last = -1;
  long at_edges = 0;
};
TitleInk title_ink(const Image& img, int below) {
  TitleInk ink;
  for (int y = 0; y < below; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Rgba p = img.pixel(x, y);
      if (p.r + p.g + p.b >= 3 * 128) continue;
      if (ink.first < 0) ink.first = y;
      ink.last = y;
      if (x < 3 || x >= img.width - 3) ++ink.at_edges;
    }
  return ink;
}

TEST(Figure, ATitleWiderThanTheImageWrapsInsteadOfBeingCutOff) {
  // Fig. 2's title is about 900 pixels wide in the title font: at the default size it is drawn
  // so, at 800 x 500 in that font at the body's size (one shorter line), at 500 x 400 broken
  // into two lines of it; never against the image's edges.
  const PlotSpec spec = figure_plot(figure_fig2(plane()));
  EglHost host;
  int one_line = 0;
  for (const auto& size : std::vector<std::pair<int, int>>{{1200, 700}, {800, 500}, {500, 400}}) {
    const int w = size.first, h = size.second;  // (a lambda below captures them)
    const std::string what = std::to_string(w) + "x" + std::to_string(h);
    const std::string png = "fig2-title-" + what + ".png";
    render_plots_png({spec}, 1, w, h, png);
    const Image img = read_png(png);
    PlotLayout lay;
    host.render_frames(w, h, [&](FrameInfo&) {
      lay = layout_plot(ImVec2(0, 0), ImVec2(static_cast<float>(w), static_cast<float>(h)), spec,
                        plot_style_light());
    });
    // The title ends above the data area's frame line.
    const TitleInk ink = title_ink(img, static_cast<int>(lay.area.y0) - 1);
    ASSERT_GE(ink.first, 0) << what << ": no title";
    EXPECT_EQ(ink.at_edges, 0) << what << ": title cut off at the image's edge";
    const int height = ink.last - ink.first + 1;
    if (w == 1200)
      one_line = height;
    else if (w == 800)
      EXPECT_LT(height, one_line) << what << ": expected one line at the body's size";
    else
      EXPECT_GT(height, 1.2 * one_line) << what << ": expected two lines";
  }
}

}  // namespace
}  // namespace dampbound::ui
