#pragma once
// Internal to plot.cpp: the drawing primitives of the plot widget (text, data layers,
// legend). Not part of the ui/ API; other code uses draw_plot().
#include "ui/plot.hpp"
#include "ui/plot_geometry.hpp"

#include <imgui.h>

#include <string>

namespace dampbound::ui::detail {

/// A font at a pixel size (size includes io.FontGlobalScale).
struct TextFont {
  ImFont* font = nullptr;
  float size = 13.0f;
};

/// Size of text in pixels.
ImVec2 text_size(const TextFont& f, const std::string& s);
/// Draws text with its top-left corner at pos.
void draw_text(ImDrawList* dl, const TextFont& f, ImVec2 pos, ImU32 col, const std::string& s);
/// `label` cut at the end, with "...", to at most `width` pixels in font f (UTF-8 safe).
std::string elide(const TextFont& f, const std::string& label, float width);

/// Draws text rotated 90 degrees counter-clockwise (reading upwards), centred at c.
void draw_text_vertical(ImDrawList* dl, const TextFont& f, ImVec2 c, ImU32 col,
                        const std::string& s);
/// Size of a tick label: "10" with a superscript exponent for pow10 ticks.
ImVec2 tick_label_size(const TextFont& f, const Tick& t);
/// Draws a tick label with its top-left corner at pos.
void draw_tick_label(ImDrawList* dl, const TextFont& f, ImVec2 pos, ImU32 col, const Tick& t);

/// Heat map cells (run-length merged, at most one cell per pixel), clipped to the area.
void draw_heatmap(ImDrawList* dl, const PlotLayout& lay, const PlotHeatmap& hm);
/// A shaded band between y_lo and y_hi, clipped to the area.
void draw_band(ImDrawList* dl, const PlotLayout& lay, const PlotBand& band);
/// A (maybe dashed) polyline through pixel points, drawn without miter spikes.
void draw_polyline(ImDrawList* dl, const std::vector<ImVec2>& pts, ImU32 col, float thickness,
                   bool dashed);
/// A series: projected, clipped, decimated, drawn.
void draw_series(ImDrawList* dl, const PlotLayout& lay, const PlotSeries& s);

/// Legend metrics from the font size: padding, row height, swatch width; the box of n
/// entries in columns.
struct LegendMetrics {
  float pad, row, swatch;
  explicit LegendMetrics(float fs);
  /// One column: swatch and a label `label_w` pixels wide.
  float column_width(float label_w) const;
  /// The box of `entries` entries in `columns` columns (filled row by row).
  ImVec2 box(int entries, int columns, float label_w) const;
};
/// Number of legend entries (series, bands, lines, heat map categories with a label); 0 when
/// the spec hides its legend.
int legend_count(const PlotSpec& spec);
/// Width of the widest legend label.
float legend_label_width(const PlotSpec& spec, const TextFont& f);
/// Legend box (series, bands, lines, heat map categories) where the layout put it
/// (lay.legend, lay.legend_columns; labels shortened to lay.legend_label_width).
void draw_legend(ImDrawList* dl, const PlotLayout& lay, const PlotSpec& spec,
                 const PlotStyle& style, const TextFont& f);
/// Size of the legend box in one column; (0, 0) when nothing has a label.
ImVec2 legend_size(const PlotSpec& spec, const TextFont& f);

}  // namespace dampbound::ui::detail
