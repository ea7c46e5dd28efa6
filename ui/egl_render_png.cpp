#include "ui/egl_host.hpp"
#include "ui/figure.hpp"
#include "ui/render_png.hpp"

namespace dampbound::ui {

std::string render_plots_png(const std::vector<PlotSpec>& plots, int columns, int width,
                             int height, const std::string& path) {
  EglHost host;
  const Image img = host.render_frames(width, height, plot_grid_frame(plots, columns));
  write_png_atomic(img, path);
  return host.gl_renderer();
}

}  // namespace dampbound::ui
