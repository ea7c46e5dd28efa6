#pragma once
// A stability map panel (core/sweep/map.hpp, plain data) as a PlotSpec: restored cells shaded
// by iteration, not restored, diverged, and the boundary lines drawn over them. Shared by
// `dampbound map` / `sweep --map` (headless) and the tuner's Map tab.
#include "core/sweep/map.hpp"
#include "ui/plot_spec.hpp"

namespace dampbound::ui {

/// Colour of a restored cell: light green when restored in few iterations, dark green near
/// the protocol's limit `max_iterations` (log scale of the iteration).
ImU32 map_restored_color(double iterations, int max_iterations);

/// The plot of one map panel: cells coloured by outcome under `rule` (SPEC 8: settled, entered
/// then left, never entered, diverged; or the paper's restored, not restored, diverged), lines
/// by kind (the paper's bound black dashed, the exact linear limit blue, the dt limit violet
/// dashed). With `with_legend`
/// the outcome swatches and every line are in a legend outside the plot; else only the lines
/// other than the paper's, bottom right.
PlotSpec map_panel_plot(const MapPanel& panel, int max_iterations, bool with_legend,
                        StopRule rule = StopRule::first_entry);

}  // namespace dampbound::ui
