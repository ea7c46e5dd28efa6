// The stability map drawn into a PNG through the headless EGL host: compiled where the build
// has the UI (app/CMakeLists.txt; map_png_none.cpp otherwise).
#include <algorithm>
#include <cmath>

#include "app/map_png.hpp"
#include "ui/egl_host.hpp"
#include "ui/map_plot.hpp"
#include "ui/plot.hpp"

namespace dampbound::app {

bool map_png_available() { return true; }

/// The paper's layout: the kappa/m panel across the top (its legend beside it), the (m, kappa)
/// panels side by side below. With --axes (map.side_by_side) every panel in one row. Either
/// way every part of the image holds a plot.
void render_map_png(const StabilityMap& map, const std::string& png, int width, int height) {
  std::vector<ui::PlotSpec> plots;
  for (size_t k = 0; k < map.panels.size(); ++k)
    plots.push_back(ui::map_panel_plot(map.panels[k], map.max_iterations, k == 0, map.rule));
  const int n = static_cast<int>(plots.size());
  const bool row = map.side_by_side;
  if (!row) plots.front().title = map.title + " - " + plots.front().title;
  const int below = row ? 0 : n - 1;  // panels under the top one
  if (width <= 0) width = row ? std::min(2400, 900 * n) : below >= 3 ? 2100 : 1800;
  if (height <= 0) height = below > 0 ? 1400 : 800;
  const ui::PlotStyle style = ui::plot_style_light();
  ui::EglHost host;
  const ui::Image img = host.render_frames(width, height, [&](ui::FrameInfo& info) {
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    const float w = static_cast<float>(info.width), h = static_cast<float>(info.height);
    dl->AddRectFilled(ImVec2(0, 0), ImVec2(w, h), style.background);
    // The row of side-by-side panels: all of them in --axes mode, else those below the top.
    const int first = row ? 0 : 1, count = row ? n : below;
    const float top = row || below == 0 ? 0.0f : std::floor(0.45f * h);
    if (!row) ui::draw_plot(dl, ImVec2(0, 0), ImVec2(w, below > 0 ? top : h), plots.front(), style);
    for (int k = 0; k < count; ++k) {
      const float cw = std::floor(w / static_cast<float>(count));
      ui::draw_plot(dl, ImVec2(cw * static_cast<float>(k), top), ImVec2(cw, h - top),
                    plots[static_cast<size_t>(first + k)], style);
    }
  });
  ui::write_png_atomic(img, png);
}

}  // namespace dampbound::app
