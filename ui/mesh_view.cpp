#include "ui/mesh_view.hpp"

#include <GL/gl.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/physics/damping_ratio.hpp"
#include "dampbound/run/scene.hpp"
#include "ui/gui_items.hpp"
#include "ui/gui_widgets.hpp"
#include "ui/mesh_pick.hpp"
#include "ui/mesh_style.hpp"
#include "ui/mesh_style.hpp"

namespace dampbound::ui {

namespace {
/// Draw-list callback: the next draw commands are opaque.
void disable_blending(const ImDrawList*, const ImDrawCmd*) {
  glDisable(GL_BLEND);
}

constexpr NodeStatus kLegend[] = {NodeStatus::within, NodeStatus::clamped, NodeStatus::violating,
                                  NodeStatus::unstabilisable, NodeStatus::fixed};

}  // namespace

void MeshView::fit(const Tuner& tuner, float aspect) {
  const Session& s = tuner.session();
  Vec3f lo, hi, lo2, hi2;
  if (!bounding_box(s.model().spec().rest, lo, hi)) return;
  // Include the scene's perturbed start so the initial bump is in view.
  if (bounding_box(initial_state(s.scene()).x, lo2, hi2)) {
    lo = lo.cwiseMin(lo2);
    hi = hi.cwiseMax(hi2);
  }
  camera_.fit_tight(lo, hi, aspect);
}

void MeshView::handle_input(Tuner& tuner, const Viewport& vp, bool hovered) {
  ImGuiIO& io = ImGui::GetIO();
  const Session& s = tuner.session();
  const Mat4f vpm = camera_.view_projection(vp.aspect());
  if (hovered && io.MouseWheel != 0.0f) camera_.zoom(io.MouseWheel);
  // A drag starts at the press: the pointer's motion in the frame of the press came before it
  // (xdotool's "mousemove X Y click 1" jumps and presses in one frame) and moves nothing.
  const bool pressed_now = drag_ == Drag::none;
  if (drag_ == Drag::none && hovered) {
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
      drag_distance_ = 0.0f;
      if (cut_tool) {
        drag_ = Drag::cut;
        cut_from_[0] = cut_to_[0] = io.MousePos.x;
        cut_from_[1] = cut_to_[1] = io.MousePos.y;
      } else {
        const auto pts = project_points(vpm, vp, s.state().x);
        const float radius = std::max(8.0f, options.point_size);
        drag_node_ = pick_node(pts, io.MousePos.x, io.MousePos.y, radius);
        drag_ = drag_node_ >= 0 ? Drag::node : Drag::orbit;
      }
    } else if (ImGui::IsMouseClicked(ImGuiMouseButton_Right) ||
               ImGui::IsMouseClicked(ImGuiMouseButton_Middle)) {
      drag_ = Drag::pan;
    }
  }
  const ImVec2 d = io.MouseDelta;
  const bool moved = !pressed_now && std::isfinite(d.x) && std::isfinite(d.y) &&
                     (d.x != 0.0f || d.y != 0.0f);
  if (moved && drag_ != Drag::none) drag_distance_ += std::abs(d.x) + std::abs(d.y);
  switch (drag_) {
    case Drag::none:
      break;
    case Drag::orbit:
      if (moved) camera_.orbit(d.x, d.y);
      if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) drag_ = Drag::none;
      break;
    case Drag::pan:
      if (moved) camera_.pan(d.x, d.y, vp.h);
      if (!ImGui::IsMouseDown(ImGuiMouseButton_Right) &&
          !ImGui::IsMouseDown(ImGuiMouseButton_Middle))
        drag_ = Drag::none;
      break;
    case Drag::node: {
      if (drag_node_ >= s.model().spec().node_count()) {  // the scene changed under the mouse
        drag_ = Drag::none;
        break;
      }
      if (moved && drag_distance_ >= 3.0f) {
        const Vec3f p = s.state().x[static_cast<size_t>(drag_node_)].cast<float>();
        const ScreenPoint sp = project(vpm, vp, p);
        if (sp.visible) {
          const Vec3f off = camera_.view_plane_offset(d.x, d.y, sp.depth, vp.h);
          tuner.displace(drag_node_, off.cast<double>());
        }
      }
      if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        tuner.watch(drag_node_);  // a click watches; a drag watches what it moved
        drag_ = Drag::none;
      }
      break;
    }
    case Drag::cut:
      cut_to_[0] = io.MousePos.x;
      cut_to_[1] = io.MousePos.y;
      if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        drag_ = Drag::none;
        if (drag_distance_ >= 3.0f) {
          const auto pts = project_points(vpm, vp, s.state().x);
          tuner.cut(springs_crossing_screen(s.model(), pts, Vec2f(cut_from_[0], cut_from_[1]),
                                            Vec2f(cut_to_[0], cut_to_[1])));
        }
      }
      break;
  }
}

void MeshView::draw_overlays(const Tuner& tuner, const Viewport& vp) const {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 tl(vp.x, vp.y), br(vp.x + vp.w, vp.y + vp.h);
  dl->PushClipRect(tl, br, true);
  const Session& s = tuner.session();
  const Mat4f vpm = camera_.view_projection(vp.aspect());
  // The watched node: a ring and its index.
  const int w = s.watched();
  if (w >= 0 && w < s.model().spec().node_count()) {
    const ScreenPoint p = project(vpm, vp, s.state().x[static_cast<size_t>(w)].cast<float>());
    if (p.visible) {
      const float r = options.point_size * 0.5f + 5.0f;
      dl->AddCircle(ImVec2(p.x, p.y), r, watched_color(), 24, 2.0f);
      dl->AddText(ImVec2(p.x + r + 3.0f, p.y - r - 14.0f), watched_color(),
                  ("watched #" + std::to_string(w)).c_str());
    }
  }
  // The cut line while dragging.
  if (drag_ == Drag::cut) {
    dl->AddLine(ImVec2(cut_from_[0], cut_from_[1]), ImVec2(cut_to_[0], cut_to_[1]),
                IM_COL32(255, 80, 60, 255), 2.5f);
  }
  // An axis triad in the lower-left corner (x red, y green, z blue).
  const ImVec2 o(tl.x + 40.0f, br.y - 40.0f);
  const Mat4f view = camera_.view();
  const ImU32 axis_col[3] = {IM_COL32(230, 80, 80, 255), IM_COL32(90, 200, 90, 255),
                             IM_COL32(90, 140, 255, 255)};
  const char* axis_name[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3f e = view.block<3, 3>(0, 0).col(a) * 26.0f;
    const ImVec2 end(o.x + e.x(), o.y - e.y());
    dl->AddLine(o, end, axis_col[a], 2.0f);
    dl->AddText(ImVec2(end.x + 2.0f, end.y - 8.0f), axis_col[a], axis_name[a]);
  }
  // The colour legend in the upper-left corner.
  const float line = ImGui::GetTextLineHeight() + 2.0f;
  float width = 0.0f;
  for (NodeStatus st : kLegend) width = std::max(width, ImGui::CalcTextSize(status_label(st)).x);
  width = std::max(width, ImGui::CalcTextSize(unguaranteed_label()).x);
  const ImVec2 box0(tl.x + 8.0f, tl.y + 8.0f);
  const ImVec2 box1(box0.x + width + 38.0f, box0.y + line * 6.0f + 10.0f);
  dl->AddRectFilled(box0, box1, IM_COL32(20, 22, 26, 200), 4.0f);
  for (int i = 0; i < 6; ++i) {  // the five states, then SPEC 9's
    const ImVec2 c(box0.x + 14.0f, box0.y + 5.0f + line * (static_cast<float>(i) + 0.5f));
    dl->AddCircleFilled(c, 5.0f, i < 5 ? status_color(kLegend[i]) : unguaranteed_color(), 16);
    dl->AddText(ImVec2(c.x + 12.0f, c.y - line * 0.5f + 1.0f), IM_COL32(230, 230, 230, 255),
                i < 5 ? status_label(kLegend[i]) : unguaranteed_label());
  }
  dl->PopClipRect();
  // Tooltips for the legend entries.
  const ImVec2 m = ImGui::GetIO().MousePos;
  if (m.x >= box0.x && m.x <= box1.x && m.y >= box0.y && m.y <= box1.y &&
      ImGui::IsWindowHovered()) {
    const int i = std::clamp(static_cast<int>((m.y - box0.y - 5.0f) / line), 0, 5);
    ImGui::SetTooltip("%s", i < 5 ? status_help(kLegend[i]) : unguaranteed_help());
  }
}

void MeshView::node_tooltip(const Tuner& tuner, const Viewport& vp) const {
  const Session& s = tuner.session();
  const ImVec2 m = ImGui::GetIO().MousePos;
  const auto pts = project_points(camera_.view_projection(vp.aspect()), vp, s.state().x);
  const int n = pick_node(pts, m.x, m.y, std::max(8.0f, options.point_size));
  if (n < 0) return;
  const size_t i = static_cast<size_t>(n);
  const ScreenPoint& p = pts[i];
  ImGui::GetWindowDrawList()->AddCircle(ImVec2(p.x, p.y), options.point_size * 0.5f + 3.0f,
                                        IM_COL32(255, 255, 255, 160), 16, 1.5f);
  const StepWorkspace& ws = s.workspace();
  const NodeStatus st = i < ws.status.size() ? ws.status[i] : NodeStatus::within;
  ImGui::BeginTooltip();
  ImGui::Text("node #%d: %s", n, status_label(st));
  ImGui::Text("|x - X| = %s cm", fmt(displacement(s.model(), s.state(), n)).c_str());
  ImGui::Text("lower %s, upper %s", fmt(s.model().lower_bound[i]).c_str(),
              i < ws.upper_bound.size() ? fmt(ws.upper_bound[i]).c_str() : "-");
  ImGui::Text("gamma %s, effective %s", fmt(s.model().gamma[i]).c_str(),
              i < ws.gamma_eff.size() ? fmt(ws.gamma_eff[i]).c_str() : "-");
  const double lo = s.model().lower_bound[i];  // SPEC 10: zeta_i = gamma_i / 2 sqrt(m_i kappa_i)
  ImGui::Text("zeta %s, effective %s", fmt(damping_ratio(s.model().gamma[i], lo)).c_str(),
              i < ws.gamma_eff.size() ? fmt(damping_ratio(ws.gamma_eff[i], lo)).c_str() : "-");
  if (i < ws.safe_bound.size())  // SPEC 9
    ImGui::Text("safe bound %s%s", fmt(ws.safe_bound[i]).c_str(),
                s.model().lower_bound[i] > ws.safe_bound[i] ? " < lower: not guaranteed" : "");
  ImGui::TextDisabled("click: watch it; drag: move it");
  ImGui::EndTooltip();
}

float spring_spacing_px(const ModelSpec& model, const std::vector<Vec3>& x, const Mat4f& view_proj,
                        const Viewport& vp) {
  // The median projected length of up to 256 springs spread over the list.
  std::vector<float> len;
  const size_t n = model.springs.size(), stride = std::max<size_t>(1, n / 256);
  for (size_t k = 0; k < n; k += stride) {
    const Spring& sp = model.springs[k];
    const ScreenPoint a = project(view_proj, vp, x[static_cast<size_t>(sp.i)].cast<float>());
    const ScreenPoint b = project(view_proj, vp, x[static_cast<size_t>(sp.j)].cast<float>());
    if (a.visible && b.visible) len.push_back(std::hypot(a.x - b.x, a.y - b.y));
  }
  if (len.empty()) return 1e9f;
  std::nth_element(len.begin(), len.begin() + static_cast<std::ptrdiff_t>(len.size() / 2), len.end());
  return len[len.size() / 2];
}

void MeshView::draw(Tuner& tuner) {
  const Session& s = tuner.session();
  if (fitted_scene_ != &s) {
    fitted_scene_ = &s;
    fit_pending_ = true;
  }
  // Toolbar.
  bool toggle = false;
  {
    const ScopedStyleColor red(ImGuiCol_Button, IM_COL32(200, 60, 50, 255), cut_tool);
    toggle = item::button(cut_tool ? "Cut tool: ON###cut_tool" : "Cut tool###cut_tool");
  }
  if (toggle) cut_tool = !cut_tool;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Drag a line across the mesh: the springs it crosses are removed.");
  ImGui::SameLine();
  if (item::button("Fit")) fit_pending_ = true;
  same_line_if_fits(checkbox_width("springs"));
  item::checkbox("springs", &options.show_springs);
  same_line_if_fits(checkbox_width("anchors"));
  item::checkbox("anchors", &options.show_anchors);
  const float slider_w = ImGui::CalcTextSize("points 16 px").x + 24.0f;
  same_line_if_fits(slider_w);
  ImGui::SetNextItemWidth(std::max(slider_w, ImGui::GetContentRegionAvail().x));
  item::slider_float("##points", &options.point_size, 2.0f, 16.0f, "points %.0f px");
  // The view fills the rest of the window but one line of hints.
  const float hint_h = ImGui::GetTextLineHeightWithSpacing();
  ImVec2 size = ImGui::GetContentRegionAvail();
  size.y -= hint_h;
  size = ImVec2(std::max(std::floor(size.x), 32.0f), std::max(std::floor(size.y), 32.0f));
  const ImVec2 tl = ImGui::GetCursorScreenPos();
  item::invisible_button("mesh_view", size,
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                             ImGuiButtonFlags_MouseButtonMiddle);
  const bool hovered = ImGui::IsItemHovered();
  const Viewport vp{tl.x, tl.y, size.x, size.y};
  viewport_ = vp;
  if (fit_pending_) {
    fit(tuner, vp.aspect());
    fit_pending_ = false;
  }
  handle_input(tuner, vp, hovered);
  MeshDrawData d;
  d.model = &s.model();
  d.x = &s.state().x;
  d.status = &s.workspace().status;
  d.safe_bound = &s.workspace().safe_bound;
  d.topology = tuner.topology();
  if (!shade.empty()) d.shade = &shade;
  d.view_proj = camera_.view_projection(vp.aspect());
  const float spacing = spring_spacing_px(s.model(), s.state().x, d.view_proj, vp);
  // Dense meshes: lines a few pixels apart alias into moire, and points wider than the spacing
  // overlap in a pattern of their own. Below ~5 px the lines and nodes fade and the points
  // shrink to the spacing.
  d.spring_alpha = spring_alpha(spacing);
  d.point_size = std::min(options.point_size, std::max(2.0f, 0.9f * spacing));
  // Below 5 px, 4x multisampling against the moire, except on a big mesh while it plays
  // (ui/mesh_style.hpp).
  d.samples = mesh_samples(spacing, s.model().spec().springs.size(), tuner.playing());
  d.point_alpha = std::clamp((spacing - 1.5f) / 3.0f, 0.3f, 1.0f);
  d.springs = springs_drawn(options.show_springs, spacing, s.model().spec().springs.size(),
                            tuner.playing());
  springs_left_out_ = options.show_springs && !d.springs;
  d.anchors = options.show_anchors;
  const ImGuiIO& io = ImGui::GetIO();
  const int fb_w = static_cast<int>(size.x * io.DisplayFramebufferScale.x);
  const int fb_h = static_cast<int>(size.y * io.DisplayFramebufferScale.y);
  const ImageKey key{tuner.state_version(), d.topology, d.view_proj, fb_w, fb_h,
                     d.point_size,          d.springs,  d.anchors,  shade_version};
  if (texture_ == 0 || !(key == drawn_)) {  // paused and still: the last image is kept
    texture_ = renderer_.render(d, fb_w, fb_h);
    drawn_ = key;
  }
  const unsigned tex = texture_;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  if (tex != 0) {
    // The image is opaque: drawn without blending, a software rasteriser skips reading the
    // pixels under it. GL textures start at the bottom row.
    dl->AddCallback(disable_blending, nullptr);
    dl->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(tex)), tl,
                 ImVec2(tl.x + size.x, tl.y + size.y), ImVec2(0, 1), ImVec2(1, 0));
    dl->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
  } else {
    dl->AddRectFilled(tl, ImVec2(tl.x + size.x, tl.y + size.y), IM_COL32(40, 20, 20, 255));
    dl->AddText(ImVec2(tl.x + 10, tl.y + 10), IM_COL32(255, 120, 120, 255),
                "the mesh view needs OpenGL 3.3");
  }
  draw_overlays(tuner, vp);
  if (hovered && drag_ == Drag::none && !cut_tool) node_tooltip(tuner, vp);
  // The hints, shortened to the width there is.
  const char* hint = cut_tool ? "cut tool: drag a line across springs to remove them"
                              : "drag: orbit | click node: watch | drag node: move it | "
                                "right/middle drag: pan | wheel: zoom";
  const char* shorter_hints[2] = {
      cut_tool ? "drag a line: cut" : "drag: orbit | click: watch | right: pan | wheel: zoom",
      cut_tool ? "drag a line: cut" : "drag: orbit | click: watch"};
  if (springs_left_out_ && !cut_tool) {  // ui/mesh_style.hpp springs_drawn()
    hint = "springs left out while playing: too dense to tell apart (pause or zoom in)";
    shorter_hints[0] = "springs left out while playing (pause or zoom in)";
    shorter_hints[1] = "springs left out while playing";
  }
  for (const char* shorter : shorter_hints)
    if (ImGui::CalcTextSize(hint).x > ImGui::GetContentRegionAvail().x) hint = shorter;
  ImGui::TextDisabled("%s", hint);
}

}  // namespace dampbound::ui
