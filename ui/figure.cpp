#include "ui/figure.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace dampbound::ui {

namespace {
/// Background draw list, cleared to the style's background.
ImDrawList* background_list(const PlotStyle& style) {
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  if (style.background != 0) {
    dl->AddRectFilled(ImVec2(0.0f, 0.0f), ImGui::GetIO().DisplaySize, style.background);
  }
  return dl;
}
}  // namespace

void draw_plot_grid(const std::vector<PlotSpec>& specs, int columns, const PlotStyle& style) {
  if (specs.empty()) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImDrawList* dl = background_list(style);
  const int n = static_cast<int>(specs.size());
  const int cols = std::clamp(columns, 1, n);
  const int rows = (n + cols - 1) / cols;
  const float w = std::floor(display.x / static_cast<float>(cols));
  const float h = std::floor(display.y / static_cast<float>(rows));
  for (int i = 0; i < n; ++i) {
    const ImVec2 tl(w * static_cast<float>(i % cols), h * static_cast<float>(i / cols));
    draw_plot(dl, tl, ImVec2(w, h), specs[static_cast<size_t>(i)], style);
  }
}

FrameFn plot_frame(PlotSpec spec, PlotStyle style) {
  return [spec = std::move(spec), style](FrameInfo&) {
    draw_plot(background_list(style), ImVec2(0.0f, 0.0f), ImGui::GetIO().DisplaySize, spec, style);
  };
}

FrameFn plot_grid_frame(std::vector<PlotSpec> specs, int columns, PlotStyle style) {
  return [specs = std::move(specs), columns, style](FrameInfo&) {
    draw_plot_grid(specs, columns, style);
  };
}

}  // namespace dampbound::ui
