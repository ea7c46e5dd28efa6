#include "ui/map_plot.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace dampbound::ui {

namespace {
const ImU32 kNotRestored = IM_COL32(253, 190, 133, 255);
const ImU32 kDiverged = IM_COL32(203, 24, 29, 255);
const ImU32 kEnteredLeft = IM_COL32(150, 80, 160, 255);  // SPEC 8: entered, then left
const ImU32 kFast = IM_COL32(199, 233, 192, 255);
const ImU32 kSlow = IM_COL32(0, 90, 50, 255);

}  // namespace

ImU32 map_restored_color(double iterations, int max_iterations) {
  const double t =
      max_iterations > 1
          ? std::clamp(std::log(std::max(iterations, 1.0)) / std::log(max_iterations), 0.0, 1.0)
          : 0.0;
  auto mix = [t](int shift) {
    const double a = (kFast >> shift) & 0xFF, b = (kSlow >> shift) & 0xFF;
    return static_cast<unsigned>(std::lround(a + (b - a) * t));
  };
  return IM_COL32(mix(IM_COL32_R_SHIFT), mix(IM_COL32_G_SHIFT), mix(IM_COL32_B_SHIFT), 255);
}

PlotSpec map_panel_plot(const MapPanel& p, int max_iterations, bool with_legend, StopRule rule) {
  PlotSpec s;
  s.title = p.title;
  s.x.label = p.x_label;
  s.x.log = p.x_log;
  s.x.min = p.x_edges.front();
  s.x.max = p.x_edges.back();
  s.y.label = p.y_label;
  s.y.log = p.y_log;
  s.y.min = p.y_edges.front();
  s.y.max = p.y_edges.back();
  s.heatmap.x_edges = p.x_edges;
  s.heatmap.y_edges = p.y_edges;
  s.heatmap.cell_color.resize(p.cells.size(), 0);
  for (size_t c = 0; c < p.cells.size(); ++c) {
    switch (p.cells[c]) {
      case MapCell::empty:
        break;
      case MapCell::restored:
        s.heatmap.cell_color[c] = map_restored_color(p.iterations[c], max_iterations);
        break;
      case MapCell::not_restored:
        s.heatmap.cell_color[c] = kNotRestored;
        break;
      case MapCell::diverged:
        s.heatmap.cell_color[c] = kDiverged;
        break;
      case MapCell::entered_left:
        s.heatmap.cell_color[c] = kEnteredLeft;
        break;
    }
  }
  if (with_legend) {
    const std::string n = std::to_string(max_iterations);
    if (rule == StopRule::settled)
      s.heatmap.legend = {{"settled early", kFast},
                          {"settled near the limit (" + n + ")", kSlow},
                          {"entered the band, then left", kEnteredLeft},
                          {"never entered in " + n + " iterations", kNotRestored},
                          {"diverged", kDiverged}};
    else
      s.heatmap.legend = {{"restored in few iterations", kFast},
                          {"restored near the limit (" + n + ")", kSlow},
                          {"not restored in " + n + " iterations", kNotRestored},
                          {"diverged", kDiverged}};
  }
  for (const MapLine& l : p.lines) {
    PlotSeries ser;
    ser.label = with_legend || l.kind != MapLineKind::paper ? l.label : "";
    ser.x = l.x;
    ser.y = l.y;
    switch (l.kind) {
      case MapLineKind::paper:
        ser.color = IM_COL32(0, 0, 0, 255);
        ser.dashed = true;
        ser.thickness = 3.0f;
        break;
      case MapLineKind::exact_linear:
        ser.color = IM_COL32(31, 80, 200, 255);
        ser.thickness = 3.0f;
        break;
      case MapLineKind::safe:  // SPEC 9's sufficient bound: inside the exact limit, green
        ser.color = IM_COL32(20, 140, 60, 255);
        ser.dashed = true;
        ser.thickness = 2.5f;
        break;
      case MapLineKind::dt_limit:
        ser.color = IM_COL32(148, 40, 180, 255);
        ser.dashed = true;
        ser.thickness = 2.5f;
        break;
    }
    s.series.push_back(ser);
  }
  s.legend = with_legend ? LegendPos::Outside : LegendPos::Above;  // inside, a key covers cells
  return s;
}

}  // namespace dampbound::ui
