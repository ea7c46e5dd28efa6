#pragma once
// Headless figures in one call: plots -> EGL frame -> PNG written whole or not at all.
#include <string>
#include <vector>

#include "ui/plot_spec.hpp"

namespace dampbound::ui {

/// Renders the plots on a grid of `columns` columns into a width x height PNG at `path`
/// through the headless EGL host. Throws std::runtime_error with a one-line reason when EGL or
/// the file fails. Returns the renderer's name (e.g. "llvmpipe ...") for logs.
std::string render_plots_png(const std::vector<PlotSpec>& plots, int columns, int width,
                             int height, const std::string& path);

}  // namespace dampbound::ui
