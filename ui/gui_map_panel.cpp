// The tuner's "Map" tab: the outcome over a 2-D log window around the current parameters
// (ui/tuner_map.hpp, computed on a worker), drawn as `dampbound map` draws a sweep's map
// (ui/map_plot.hpp), with the current point marked; a click on a cell sets its parameters.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/io/report.hpp"
#include "ui/gui_app.hpp"
#include "ui/gui_items.hpp"
#include "ui/gui_widgets.hpp"
#include "ui/map_plot.hpp"
#include "ui/plot.hpp"

namespace dampbound::ui {

namespace {

/// The cell of `edges` holding v, or -1.
int cell_of(const std::vector<double>& edges, double v) {
  for (size_t i = 0; i + 1 < edges.size(); ++i)
    if (v >= edges[i] && v <= edges[i + 1]) return static_cast<int>(i);
  return -1;
}

/// An axis picker; the other axis's parameter cannot be chosen.
void axis_combo(const char* label, MapParam* p, MapParam other) {
  auto name = [](void*, int k, const char** out) {
    *out = to_string(kMapParams[k]);
    return true;
  };
  int v = static_cast<int>(*p);
  ImGui::SetNextItemWidth(ImGui::CalcTextSize(to_string(*p)).x + ImGui::GetFrameHeight() * 1.6f);
  if (item::combo(label, &v, name, nullptr, IM_ARRAYSIZE(kMapParams)) &&
      v != static_cast<int>(other))
    *p = static_cast<MapParam>(v);
}

}  // namespace

void GuiApp::map_panel() {
  Tuner& t = *tuner_;
  MapView& v = map_view_;
  axis_combo("y##map_y", &v.y, v.x);
  ImGui::SameLine();
  axis_combo("x##map_x", &v.x, v.y);
  // The window's reach and the resolution: on the same line when there is room.
  const float controls_w = ImGui::CalcTextSize("+-0.00 decades 64 x 64").x + 80.0f;
  const float line_end = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  if (line_end - ImGui::GetItemRectMax().x > controls_w) ImGui::SameLine();
  float span = static_cast<float>(v.decades);
  ImGui::SetNextItemWidth(std::max(80.0f, ImGui::CalcTextSize("+-0.00 decades").x + 16.0f));
  if (item::slider_float("##decades", &span, 0.25f, 3.0f, u8"\u00B1%.2f decades"))
    v.decades = std::round(span * 4.0f) / 4.0;  // quarter decades: no restart per pixel
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("How far the window reaches around the current point");
  ImGui::SameLine();
  static const int sizes[] = {16, 24, 32, 48, 64};
  int pick = 2;
  for (int i = 0; i < 5; ++i)
    if (sizes[i] == v.finest) pick = i;
  ImGui::SetNextItemWidth(ImGui::CalcTextSize("64 x 64").x + ImGui::GetFrameHeight() * 1.6f);
  if (item::combo("##cells", &pick, "16 x 16\0" "24 x 24\0" "32 x 32\0" "48 x 48\0" "64 x 64\0"))
    v.finest = sizes[pick];
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Cells per axis of the finest pass");
  map_.follow(t.session().shared_scene(), t.scene_version(), t.params(), t.session().rules(), v);
  const auto r = map_.result();
  const std::string why = map_.unsupported();
  std::string line;
  if (!why.empty()) {
    wrapped_colored(gui_amber(), ("no map: " + why).c_str());
    return;
  }
  // Progress: the passes double the cells per axis from 8 up to the finest.
  int passes = 1;
  for (int c = 8; c < v.finest; c *= 2) ++passes;
  const bool busy = map_.busy();
  if (r) {
    const int n = static_cast<int>(r->x_edges.size()) - 1;
    // The next pass has twice the cells per axis: about four times this pass's time.
    line = std::to_string(n) + " x " + std::to_string(n) + " trials, " + fmt(r->seconds) + " s" +
           (busy ? ", computing pass " + std::to_string(std::min(r->pass + 1, passes)) + " of " +
                       std::to_string(passes) + " (" + std::to_string(2 * n) + " x " +
                       std::to_string(2 * n) + " trials, about " + fmt(4 * r->seconds) + " s)..."
                 : r->finest ? "" : " (cancelled before the finest pass)");
  } else {
    line = busy ? "computing pass 1 of " + std::to_string(passes) + "..." : "cancelled";
  }
  if (busy) {
    if (item::small_button("Cancel")) map_.cancel();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Stop computing; the last finished pass stays.\nA change of the window "
                        "or the parameters starts it again.");
    ImGui::SameLine();
  }
  if (t.session().springs_cut() > 0) line += "  (the scene as loaded: hand cuts not included)";
  if (r && r->plain) line += "  (each cell runs step(): slower)";
  ImGui::TextDisabled("%s", line.c_str());
  if (!r || r->view.x != v.x || r->view.y != v.y) return;
  PlotSpec spec = map_panel_plot(map_result_panel(*r), r->max_iterations, true, r->rule);
  spec.title.clear();
  // The key as one wrapping line of swatches above the plot: a legend box would take a third
  // of a panel this size, or cover the cells.
  spec.legend = LegendPos::Hidden;
  std::vector<LegendSwatch> key = spec.heatmap.legend;  // short names, the full ones on hover
  const std::vector<const char*> short_names =
      r->rule == StopRule::settled
          ? std::vector<const char*>{"settled early", "near the limit", "entered, then left",
                                     "never entered", "diverged"}
          : std::vector<const char*>{"restored: few iterations", "near the limit",
                                     "not restored", "diverged"};
  for (size_t k = 0; k < key.size() && k < short_names.size(); ++k)
    key[k].label = short_names[k];
  for (size_t k = 0; k < r->lines.size() && k < spec.series.size(); ++k)
    key.push_back({r->lines[k].kind == MapLineKind::paper  ? "lower bound"
                   : r->lines[k].kind == MapLineKind::safe ? "safe bound"
                                                           : "exact limit",
                   spec.series[k].color});
  key.push_back({"current", IM_COL32(255, 255, 255, 255)});
  // In a short panel the key hides behind one line and shows on hover.
  const bool short_panel = ImGui::GetContentRegionAvail().y < 320.0f;
  if (short_panel) {
    ImGui::SameLine();
    ImGui::TextDisabled("| key (hover)");
    if (!ImGui::IsItemHovered()) key.clear();
    else ImGui::BeginTooltip();
  }
  ImDrawList* dl = ImGui::GetWindowDrawList();  // the tooltip's, in a short panel
  const float box = ImGui::GetTextLineHeight() * 0.8f;
  for (size_t k = 0; k < key.size(); ++k) {
    const std::string& text = key[k].label;
    const float w = box + ImGui::GetStyle().ItemInnerSpacing.x + ImGui::CalcTextSize(text.c_str()).x;
    if (k > 0 && !short_panel) same_line_if_fits(w);
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float y = p.y + (ImGui::GetTextLineHeight() - box) * 0.5f;
    dl->AddRectFilled(ImVec2(p.x, y), ImVec2(p.x + box, y + box), key[k].color);
    dl->AddRect(ImVec2(p.x, y), ImVec2(p.x + box, y + box), IM_COL32(200, 200, 200, 160));
    ImGui::Dummy(ImVec2(box, ImGui::GetTextLineHeight()));
    ImGui::SameLine(0.0f, ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::TextUnformatted(text.c_str());
    if (short_panel) continue;
    if (ImGui::IsItemHovered() && k < spec.heatmap.legend.size())
      ImGui::SetTooltip("%s", spec.heatmap.legend[k].label.c_str());
    else if (ImGui::IsItemHovered() && k - spec.heatmap.legend.size() < spec.series.size())
      ImGui::SetTooltip("%s", spec.series[k - spec.heatmap.legend.size()].label.c_str());
  }
  if (short_panel && !key.empty()) ImGui::EndTooltip();
  const double cx = get_param(t.params(), v.x), cy = get_param(t.params(), v.y);
  for (int k = 0; k < 2; ++k) {
    // The current point: a cross of two lines, a dark one under a white one.
    const ImU32 c = k == 0 ? IM_COL32(0, 0, 0, 255) : IM_COL32(255, 255, 255, 255);
    const float w = k == 0 ? 4.0f : 1.5f;
    spec.ref_lines.push_back({k == 1 ? "current point" : "", LineAxis::x, cx, c, false, w});
    spec.ref_lines.push_back({"", LineAxis::y, cy, c, false, w});
  }
  const PlotLayout lay = plot_widget("map", spec, ImVec2(-1.0f, -1.0f), gui_plot_style());
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  if (!ImGui::IsItemHovered() || !lay.area.contains(mouse.x, mouse.y)) return;
  const int ix = cell_of(r->x_edges, lay.x.from_px(mouse.x));
  const int iy = cell_of(r->y_edges, lay.y.from_px(mouse.y));
  if (ix < 0 || iy < 0) return;
  const int nx = static_cast<int>(r->x_edges.size()) - 1;
  const TrialResult& cell = r->cells[static_cast<size_t>(iy * nx + ix)];
  const double x = std::sqrt(r->x_edges[ix] * r->x_edges[ix + 1]);
  const double y = std::sqrt(r->y_edges[iy] * r->y_edges[iy + 1]);
  ImGui::BeginTooltip();
  ImGui::Text("%s = %s, %s = %s", to_string(v.x), fmt(x).c_str(), to_string(v.y), fmt(y).c_str());
  RunResult as_run;  // the window's verdict colours and words for a trial
  as_run.outcome = cell.outcome;
  as_run.iterations = cell.iterations;
  as_run.first_entry = cell.first_entry;
  as_run.left_at = cell.left_at;
  as_run.settled_at = cell.settled_at;
  ImGui::TextColored(outcome_color(as_run), "%s", verdict_short(as_run).c_str());
  ImGui::TextDisabled("click: run with these values");
  ImGui::EndTooltip();
  if (ImGui::IsItemClicked(ImGuiMouseButton_Left)) {
    Params p = t.params();
    set_param(p, v.x, x);
    set_param(p, v.y, y);
    if (t.set_params(p, &param_error_)) {
      param_error_.clear();
      t.reset();
    }
  }
}

}  // namespace dampbound::ui
