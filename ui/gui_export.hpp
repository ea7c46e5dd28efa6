#pragma once
// The tuner's Export: the plots rendered offscreen as a figure (white background, the plot
// widget's light style) into a PNG, plus the CSVs of tuner_export.hpp. Renders with the GL
// context and ImGui context that are current (the window's, or the headless EGL host's), so
// it works inside a frame and needs no second context.
#include <string>
#include <vector>

#include "ui/image.hpp"
#include "ui/plot_spec.hpp"
#include "ui/tuner.hpp"
#include "ui/tuner_plots.hpp"

namespace dampbound::ui {

/// Draws `plots` on a grid of `columns` columns into an offscreen width x height framebuffer
/// with the current ImGui context's fonts and OpenGL3 backend, and reads it back. Call inside
/// an ImGui frame with the GL context current. Throws std::runtime_error on a GL failure.
Image render_plots_offscreen(const std::vector<PlotSpec>& plots, int columns, int width,
                             int height);

/// Exports the tuner's plots (PNG, light figure style) and data (CSV) to DIR/PREFIX_*, the
/// current run in the CSVs only when `current`. Returns a one-line summary of what was
/// written. Throws (InputError, std::runtime_error) with a one-line reason; nothing
/// half-written is left behind.
std::string export_runs(Tuner& tuner, const std::vector<PlotSpec>& plots, const std::string& dir,
                        const std::string& prefix, bool current = true);

/// The plots an export draws: the displacement of every visible pin (and of the current run
/// when `current`) from every step, as `figure` draws runs, and, with the current run, its
/// damping bounds.
std::vector<PlotSpec> export_plot_specs(Tuner& tuner, TunerPlotOptions options, bool current);

}  // namespace dampbound::ui
