// A build without the UI (DAMPBOUND_GUI and DAMPBOUND_EGL off) draws no map: the commands that
// would ask for one refuse the flag up front (map_png_available), and this says why if called.
#include "app/map_png.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound::app {

bool map_png_available() { return false; }

void render_map_png(const StabilityMap&, const std::string& png, int, int) {
  throw InputError(png + ": this build has no headless EGL host to draw the map (DAMPBOUND_EGL=OFF)");
}

}  // namespace dampbound::app
