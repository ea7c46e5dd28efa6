#pragma once
// The stability map of a sweep (core/sweep/map.hpp) drawn into a PNG. `map`, `sweep --map` and
// `reproduce` call it; which file defines it is the build's choice (app/CMakeLists.txt):
// map_png_egl.cpp with the headless EGL host, map_png_none.cpp without the UI.
#include <string>

#include "core/sweep/map.hpp"

namespace dampbound::app {

/// Whether this build can draw maps (it has the headless EGL host).
bool map_png_available();

/// Draws `map` into the PNG `png`, written atomically: the paper's layout (the kappa/m panel
/// across the top, the (m, kappa) panels below) or, with map.side_by_side, every panel in one
/// row. width or height <= 0: sized from the panel count. Throws on failure.
void render_map_png(const StabilityMap& map, const std::string& png, int width = 0, int height = 0);

}  // namespace dampbound::app
