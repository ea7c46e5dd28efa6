#pragma once
// Frame functions for figures: plots that fill the whole display, for the headless host
// (figure PNGs, the stability map) or a window.
#include "ui/frame_renderer.hpp"
#include "ui/plot.hpp"

#include <vector>

namespace dampbound::ui {

/// Draws the plots on a grid of `columns` columns filling the display (background draw list,
/// so no ImGui window is involved and the first frame is already complete). Call inside a
/// frame function.
void draw_plot_grid(const std::vector<PlotSpec>& specs, int columns, const PlotStyle& style);

/// A frame function that draws one plot filling the display.
FrameFn plot_frame(PlotSpec spec, PlotStyle style = plot_style_light());

/// A frame function that draws several plots on a grid of `columns` columns.
FrameFn plot_grid_frame(std::vector<PlotSpec> specs, int columns,
                        PlotStyle style = plot_style_light());

}  // namespace dampbound::ui
