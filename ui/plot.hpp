#pragma once
// The plot widget: draws a PlotSpec (ui/plot_spec.hpp) with ImGui draw lists, so the same
// plot appears in the GUI window and in headless figures. Layout and geometry come from the
// pure functions in ui/plot_math.hpp.
#include "ui/plot_math.hpp"
#include "ui/plot_spec.hpp"

#include <imgui.h>

#include <vector>

namespace dampbound::ui {

/// Colours and fonts of a plot. Fonts left null mean the current font and title_font().
struct PlotStyle {
  ImU32 background = 0;       ///< whole widget (0: transparent, the window shows through)
  ImU32 plot_background = 0;  ///< the data area
  ImU32 frame = 0;            ///< data area border and tick marks
  ImU32 grid = 0;             ///< major grid lines
  ImU32 grid_minor = 0;       ///< minor grid lines (log axes)
  ImU32 text = 0;
  ImU32 legend_background = 0;
  ImU32 legend_border = 0;
  ImU32 crosshair = 0;  ///< hover lines in plot_widget
  ImFont* font = nullptr;
  ImFont* title_font = nullptr;
  bool draw_curves = true;  ///< series and reference lines (off: the render test's reference)
  bool draw_legend = true;  ///< the legend box (off: the render test's reference)
};

/// White background, dark text: figures and papers.
PlotStyle plot_style_light();
/// Dark background, light text: the interactive GUI's dark theme.
PlotStyle plot_style_dark();
/// Light or dark after the current ImGui style (see current_theme_is_dark()).
PlotStyle plot_style_current();

/// Where things landed: the data area, the data<->pixel maps and the ticks drawn.
struct PlotLayout {
  PixelRect frame;  ///< the whole widget
  PixelRect area;   ///< the data area (inside the axes)
  AxisMap x;        ///< data x -> screen x
  AxisMap y;        ///< data y -> screen y (px_lo is the bottom)
  std::vector<Tick> x_ticks;
  std::vector<Tick> y_ticks;
  LegendPos legend_pos = LegendPos::Hidden;  ///< where the legend went (Hidden: none)
  PixelRect legend;                          ///< the legend box in pixels
  int legend_columns = 1;                    ///< entries per row (Above)
  float legend_label_width = 0.0f;           ///< labels are shortened to this width
};

/// How many pixels of the series and reference lines (their width and anti-aliased edge
/// included) lie inside `box` when the plot is drawn with layout `lay`: 0 means a legend box
/// there hides no curve. Dashed lines count as solid.
size_t curve_pixels_under(const PlotLayout& lay, const PlotSpec& spec, const PixelRect& box);

/// Computes the layout of `spec` in the rectangle (top_left, size) for the current font,
/// without drawing. Needs an ImGui context with a built font atlas (inside a frame).
PlotLayout layout_plot(ImVec2 top_left, ImVec2 size, const PlotSpec& spec,
                       const PlotStyle& style);

/// Draws the whole plot (title, axes, ticks, grid, heat map, bands, lines, series, legend)
/// into `dl` inside the rectangle (top_left, size). Data is clipped to the data area; series
/// longer than about twice the area width in pixels are min/max decimated per pixel column.
PlotLayout draw_plot(ImDrawList* dl, ImVec2 top_left, ImVec2 size, const PlotSpec& spec,
                     const PlotStyle& style = plot_style_current());

/// The plot as an ImGui item at the cursor of the current window. size.x <= 0 takes the
/// available width, size.y <= 0 the available height. Hovering the data area draws a
/// crosshair and a tooltip with the data (x, y) under the mouse.
PlotLayout plot_widget(const char* id, const PlotSpec& spec, ImVec2 size = ImVec2(-1.0f, 0.0f),
                       const PlotStyle& style = plot_style_current());

}  // namespace dampbound::ui
