#pragma once
// Plain-data description of a 2-D plot: what to draw, not how. Filled by the app (from a
// Trace, a bounds sweep, a stability map) and drawn by draw_plot() in ui/plot.hpp, in a
// window or headless. Nothing here needs a GL context.
#include <imgui.h>

#include <optional>
#include <string>
#include <vector>

namespace dampbound::ui {

/// A polyline through (x[i], y[i]). A point whose x or y is not finite (or <= 0 on a log
/// axis) is skipped and breaks the line there. x need not be monotonic.
struct PlotSeries {
  std::string label;      ///< legend text; empty: not in the legend
  std::vector<double> x;  ///< data x, same length as y
  std::vector<double> y;  ///< data y
  ImU32 color = IM_COL32(31, 119, 180, 255);
  float thickness = 2.0f;  ///< line width in pixels
  bool dashed = false;
};

/// Shaded region between two curves sampled at the same x: y_lo[i] <= y <= y_hi[i]. Used for
/// the feasible damping band between the lower (eq. 5) and upper (eq. 6) bound.
/// y_hi = +inf means "to the top of the plot", y_lo = -inf (or <= 0 on a log axis) "to the
/// bottom"; NaN anywhere drops the samples on either side. Where y_lo > y_hi the band is empty.
struct PlotBand {
  std::string label;
  std::vector<double> x;
  std::vector<double> y_lo;
  std::vector<double> y_hi;
  ImU32 color = IM_COL32(44, 160, 44, 70);  ///< usually translucent
};

/// The axis a reference line marks a value of: x (a vertical line) or y (a horizontal one).
enum class LineAxis { x, y };

/// A line across the whole plot at one data value, in either orientation (as ImPlot's
/// PlotInfLines): horizontal at a y (the 1 % restore threshold), vertical at an x (the
/// iteration of a verdict).
struct PlotRefLine {
  std::string label;
  LineAxis axis = LineAxis::y;
  double at = 0.0;  ///< the data value on `axis`
  ImU32 color = IM_COL32(127, 127, 127, 255);
  bool dashed = true;
  float thickness = 1.5f;
};

/// One entry of a discrete colour legend (e.g. "diverged" in red).
struct LegendSwatch {
  std::string label;
  ImU32 color = 0;
};

/// Cells of a 2-D grid, each one flat colour: cell (ix, iy) spans
/// [x_edges[ix], x_edges[ix+1]] x [y_edges[iy], y_edges[iy+1]] and has colour
/// cell_color[iy * nx + ix] with nx = x_edges.size() - 1 (row-major, row = y index).
/// Fully transparent cells are not drawn. Edges must be increasing.
struct PlotHeatmap {
  std::vector<double> x_edges;
  std::vector<double> y_edges;
  std::vector<ImU32> cell_color;
  std::vector<LegendSwatch> legend;  ///< discrete categories shown in the legend box
  int nx() const { return x_edges.size() < 2 ? 0 : static_cast<int>(x_edges.size()) - 1; }
  int ny() const { return y_edges.size() < 2 ? 0 : static_cast<int>(y_edges.size()) - 1; }
  bool empty() const { return nx() == 0 || ny() == 0; }
};

/// One axis: label, scale and optional fixed ends (an unset end comes from the data).
struct AxisSpec {
  std::string label;
  bool log = false;         ///< log10 scale; non-positive data is skipped
  std::optional<double> min;
  std::optional<double> max;
};

/// Where the legend box goes. Auto takes the first inside corner (top right, top left,
/// bottom right, bottom left) under which no curve pixel lies; where every corner would hide
/// one, it goes Outside when that leaves the data area most of the width, else Above.
/// Outside puts it right of the plot area, Above in columns between the title and the plot
/// area; both shrink the area.
enum class LegendPos { Auto, TopRight, TopLeft, BottomRight, BottomLeft, Outside, Above, Hidden };

/// Everything one plot shows. Drawing order: heatmap, bands, grid, reference lines, series, legend.
struct PlotSpec {
  std::string title;
  AxisSpec x;
  AxisSpec y;
  std::vector<PlotSeries> series;
  std::vector<PlotBand> bands;
  std::vector<PlotRefLine> ref_lines;  ///< drawn vertical ones first, listed horizontal ones first
  PlotHeatmap heatmap;
  LegendPos legend = LegendPos::Auto;
};

/// The i-th colour of a 10-colour qualitative palette (wraps around), opaque.
ImU32 palette_color(int i);

/// `color` with its alpha replaced by `alpha` (0..255).
ImU32 with_alpha(ImU32 color, int alpha);

}  // namespace dampbound::ui
