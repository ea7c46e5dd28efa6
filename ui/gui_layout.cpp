#include "ui/gui_layout.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dampbound::ui {

namespace {

bool same_rect(const PanelRect& a, const PanelRect& b) {
  return std::abs(a.x - b.x) <= 1 && std::abs(a.y - b.y) <= 1 && std::abs(a.w - b.w) <= 1 &&
         std::abs(a.h - b.h) <= 1;
}

const PanelRect* find(const std::vector<PanelRect>& rects, const std::string& name) {
  for (const PanelRect& r : rects)
    if (r.name == name) return &r;
  return nullptr;
}

}  // namespace

bool compact_layout(float height) {
  return height < kCompactLayoutHeight;
}

std::vector<PanelRect> default_layout(float W, float H) {
  const bool compact = compact_layout(H);
  const float left = std::clamp(std::floor(W * 0.245f), 330.0f, 430.0f);
  const float R = W - left, top = std::floor(H * (compact ? 0.5f : 0.56f));
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

std::vector<PanelRect> panels_after_resize(const std::vector<PanelRect>& drawn, float from_w,
                                           float from_h, float to_w, float to_h) {
  const std::vector<PanelRect> before = default_layout(from_w, from_h);
  const std::vector<PanelRect> after = default_layout(to_w, to_h);
  const float sx = to_w / from_w, sy = to_h / from_h;
  std::vector<PanelRect> out;
  for (const PanelRect& d : drawn) {
    const PanelRect* was = find(before, d.name);
    const PanelRect* now = find(after, d.name);
    if (was != nullptr && now != nullptr && same_rect(d, *was))
      out.push_back(*now);
    else
      out.push_back({d.name, std::floor(d.x * sx), std::floor(d.y * sy), std::floor(d.w * sx),
                     std::floor(d.h * sy)});
  }
  return out;
}

std::vector<PanelRect> remembered_panels(const std::string& imgui_ini) {
  std::vector<PanelRect> out;
  std::istringstream in(imgui_ini);
  std::string line, name;
  bool has_pos = false, has_size = false;
  PanelRect r{"", 0, 0, 0, 0};
  auto flush = [&] {
    if (!name.empty() && has_pos && has_size) {  // a later section wins, as in ImGui's loader
      r.name = name;
      const auto same =
          std::find_if(out.begin(), out.end(), [&](const PanelRect& o) { return o.name == name; });
      if (same != out.end())
        *same = r;
      else
        out.push_back(r);
    }
    name.clear();
    has_pos = has_size = false;
  };
  auto pair = [](const std::string& text, float& a, float& b) {
    float x = 0, y = 0;
    char comma = 0;
    std::istringstream v(text);
    if (!(v >> x >> comma >> y) || comma != ',' || !std::isfinite(x) || !std::isfinite(y))
      return false;
    a = x;
    b = y;
    return true;
  };
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("[", 0) == 0) {
      flush();
      const std::string head = "[Window][";
      if (line.rfind(head, 0) == 0 && line.size() > head.size() && line.back() == ']')
        name = line.substr(head.size(), line.size() - head.size() - 1);
    } else if (!name.empty() && line.rfind("Pos=", 0) == 0) {
      has_pos = pair(line.substr(4), r.x, r.y);
    } else if (!name.empty() && line.rfind("Size=", 0) == 0) {
      has_size = pair(line.substr(5), r.w, r.h) && r.w > 0 && r.h > 0;
    }
  }
  flush();
  return out;
}

void GuiLayout::set_remembered_size(float width, float height) {
  laid_w_ = width;
  laid_h_ = height;
}

void GuiLayout::update(float W, float H) {
  default_ = default_layout(W, H);
  compact_ = compact_layout(H);
  if (compact_ && std::find(hidden_.begin(), hidden_.end(), "Status") == hidden_.end()) {
    hidden_.push_back("Status");  // not drawn: it must not follow resizes from a stale place
    drawn_.erase(std::remove_if(drawn_.begin(), drawn_.end(),
                                [](const PanelRect& r) { return r.name == "Status"; }),
                 drawn_.end());
  }
  follow_.clear();
  if (drawn_.empty()) return;  // nothing drawn yet: no rectangles to move
  if (laid_w_ > 0 && laid_h_ > 0 && (W != laid_w_ || H != laid_h_) && !reset_)
    follow_ = panels_after_resize(drawn_, laid_w_, laid_h_, W, H);
  laid_w_ = W;
  laid_h_ = H;
}

std::optional<PanelRect> GuiLayout::drawn(const std::string& name) const {
  const PanelRect* r = find(drawn_, name);
  return r != nullptr ? std::optional<PanelRect>(*r) : std::nullopt;
}

bool GuiLayout::begin(const char* name, int flags) {
  // A panel that was hidden (the compact layout's Status) comes back where the layout says.
  const auto was_hidden = std::find(hidden_.begin(), hidden_.end(), name);
  const bool back = was_hidden != hidden_.end();
  if (back) hidden_.erase(was_hidden);
  const ImGuiCond cond = reset_ || back ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  auto place = [](const PanelRect* r, ImGuiCond c) {
    if (r == nullptr) return;
    ImGui::SetNextWindowPos(ImVec2(r->x, r->y), c);
    ImGui::SetNextWindowSize(ImVec2(r->w, r->h), c);
  };
  place(find(default_, name), cond);
  const auto remembered = std::find_if(remembered_.begin(), remembered_.end(),
                                       [&](const PanelRect& r) { return r.name == name; });
  if (remembered != remembered_.end()) {  // its first begin: where imgui.ini had it
    if (!reset_ && !back) place(&*remembered, ImGuiCond_Always);
    remembered_.erase(remembered);
  }
  place(find(follow_, name), ImGuiCond_Always);
  // A window that overlaps no other needs no background fill: the frame is cleared to the
  // same colour. On a software rasteriser (llvmpipe) this saves a full-screen blended fill.
  PanelRect* last = nullptr;
  for (PanelRect& r : drawn_)
    if (r.name == name) last = &r;
  bool overlaps = last == nullptr;
  for (const PanelRect& r : drawn_)
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
