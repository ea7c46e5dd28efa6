// The tuner window's layout: the default place of each panel for a window size (compact
// below kCompactLayoutHeight), panels following a resize, and ImGui::Begin at those places.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ui/gui_app.hpp"

namespace dampbound::ui {

namespace {

/// The default layout for a W x H window: controls on the left, the mesh and the envelope on
/// top, the displacement and the runs below.
std::vector<GuiApp::WindowRect> default_layout(float W, float H) {
  const float left = std::clamp(std::floor(W * 0.245f), 330.0f, 430.0f);
  const float R = W - left, top = std::floor(H * (H < kCompactLayoutHeight ? 0.5f : 0.56f));
  const bool compact = H < kCompactLayoutHeight;
  // The runs' tabs need about 330 px; in a compact window they take the status tabs too.
  const float runs_w = compact ? std::max(std::floor(R * 0.5f), 330.0f)
                               : std::max(std::floor(R * 0.36f), std::min(330.0f, R * 0.5f));
  const float mesh_w = std::floor(R * 0.48f), disp_w = R - runs_w;
  // Compact: the parameters take the whole left column (the status moved to the runs' tabs).
  const float params_h = compact ? H : std::floor(std::clamp(535.0f, H * 0.45f, H * 0.62f));
  return {
      {"Parameters", 0, 0, left, params_h},
      {"Status", 0, params_h, left, H - params_h},
      {"Mesh view", left, 0, mesh_w, top},
      {"Damping bounds", left + mesh_w, 0, R - mesh_w, top},
      {"Displacement", left, top, disp_w, H - top},
      {"Runs", left + disp_w, top, R - disp_w, H - top},
  };
}

bool same_rect(const GuiApp::WindowRect& a, const GuiApp::WindowRect& b) {
  return std::abs(a.x - b.x) <= 1 && std::abs(a.y - b.y) <= 1 && std::abs(a.w - b.w) <= 1 &&
         std::abs(a.h - b.h) <= 1;
}
}  // namespace

void GuiApp::layout_windows(const FrameInfo& info) {
  // Remembered positions (imgui.ini) win over the default layout unless "reset layout" was
  // asked. When the window changes size, every panel follows: one still where the default
  // layout put it takes the default layout of the new size, one the user moved or resized
  // keeps its place and size in proportion.
  const float W = static_cast<float>(info.width), H = static_cast<float>(info.height);
  layout_ = default_layout(W, H);
  follow_.clear();
  if (drawn_.empty()) return;  // nothing drawn yet: no rectangles to move
  if (layout_w_ > 0 && layout_h_ > 0 && (W != layout_w_ || H != layout_h_) && !reset_layout_) {
    const std::vector<WindowRect> before = default_layout(layout_w_, layout_h_);
    const float sx = W / layout_w_, sy = H / layout_h_;
    for (const WindowRect& d : drawn_) {
      const WindowRect* was = nullptr;
      const WindowRect* now = nullptr;
      for (const WindowRect& r : before)
        if (r.name == d.name) was = &r;
      for (const WindowRect& r : layout_)
        if (r.name == d.name) now = &r;
      if (was != nullptr && now != nullptr && same_rect(d, *was))
        follow_.push_back(*now);
      else
        follow_.push_back({d.name, std::floor(d.x * sx), std::floor(d.y * sy), std::floor(d.w * sx),
                           std::floor(d.h * sy)});
    }
  }
  layout_w_ = W;
  layout_h_ = H;
}

bool GuiApp::begin(const char* name, int flags) {
  // A panel that was hidden (the compact layout's Status) comes back where the layout says.
  const auto was_hidden = std::find(hidden_.begin(), hidden_.end(), name);
  const bool back = was_hidden != hidden_.end();
  if (back) hidden_.erase(was_hidden);
  const ImGuiCond cond = reset_layout_ || back ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  for (const WindowRect& r : layout_) {
    if (r.name != name) continue;
    ImGui::SetNextWindowPos(ImVec2(r.x, r.y), cond);
    ImGui::SetNextWindowSize(ImVec2(r.w, r.h), cond);
  }
  for (const WindowRect& r : follow_) {
    if (r.name != name) continue;
    ImGui::SetNextWindowPos(ImVec2(r.x, r.y), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(r.w, r.h), ImGuiCond_Always);
  }
  // A window that overlaps no other needs no background fill: the frame is cleared to the
  // same colour. On a software rasteriser (llvmpipe) this saves a full-screen blended fill.
  WindowRect* last = nullptr;
  for (WindowRect& r : drawn_)
    if (r.name == name) last = &r;
  bool overlaps = last == nullptr;
  for (const WindowRect& r : drawn_)
    if (last != nullptr && &r != last && r.x < last->x + last->w - 1 && last->x < r.x + r.w - 1 &&
        r.y < last->y + last->h - 1 && last->y < r.y + r.h - 1)
      overlaps = true;
  if (!overlaps) flags |= ImGuiWindowFlags_NoBackground;
  const bool open = ImGui::Begin(name, nullptr, flags | ImGuiWindowFlags_NoCollapse);
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  if (last == nullptr) drawn_.push_back({name, 0, 0, 0, 0}), last = &drawn_.back();
  *last = {name, pos.x, pos.y, size.x, size.y};
  return open;
}

}  // namespace dampbound::ui
