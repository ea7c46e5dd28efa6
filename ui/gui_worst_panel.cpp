// The tuner's "Worst nodes" tab: the nodes that limit dt and gamma (SPEC 9's dt_safe_i and
// gamma_safe_i, smallest first) with what makes them small, as `bounds SCENE --worst N`
// gives them; a click on a row watches that node, as a click on it in the mesh view does.
#include <imgui.h>

#include <string>

#include "ui/gui_app.hpp"
#include "ui/gui_items.hpp"
#include "ui/gui_widgets.hpp"

namespace dampbound::ui {

void GuiApp::worst_panel() {
  Tuner& t = *tuner_;
  ImGui::SetNextItemWidth(ImGui::CalcTextSize("000000").x * 2.5f);
  item::slider_int("nodes", &worst_.count, 1, 50, "%d", ImGuiSliderFlags_Logarithmic);
  ImGui::SameLine();
  const char* orders[] = {"by dt_safe_i", "by gamma_safe_i"};
  ImGui::SetNextItemWidth(ImGui::CalcTextSize(orders[1]).x + 3 * ImGui::GetFrameHeight());
  item::combo("##order", &worst_.order, orders, 2);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("dt_safe_i: the largest dt the safe bound allows node i at its gamma_i\n"
                      "gamma_safe_i: the largest gamma_i it allows at this dt");
  const WorstNodes& w = worst_nodes_.get(t.session(), t.topology(), worst_.count);
  wrapped_colored(ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled),
                  "at rest, dt = " + fmt(t.params().dt) + " s; medians: mass " +
                      fmt(w.median_mass) + ", stiffness " + fmt(w.median_kappa) + ", edge " +
                      fmt(w.median_edge) + " cm");
  const std::vector<WorstNode>& rows = worst_.order == 0 ? w.by_dt : w.by_gamma;
  const ImGuiTableFlags tf = ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_ScrollY |
                             ImGuiTableFlags_RowBg;
  if (!ImGui::BeginTable("worst", 4, tf, ImVec2(0, ImGui::GetContentRegionAvail().y))) return;
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableSetupColumn("node", ImGuiTableColumnFlags_WidthFixed);
  ImGui::TableSetupColumn("dt_safe (s)", ImGuiTableColumnFlags_WidthFixed);
  ImGui::TableSetupColumn("gamma_safe", ImGuiTableColumnFlags_WidthFixed);
  ImGui::TableSetupColumn("cause", ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableHeadersRow();
  const int watched = t.session().watched();
  for (const WorstNode& n : rows) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    const std::string label = "#" + std::to_string(n.node);
    if (item::selectable(label.c_str(), n.node == watched)) t.watch(n.node);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("node #%d: mass %s, stiffest spring %s, shortest edge %s cm, %s\n"
                        "click: watch it (the plots and the status follow it)",
                        n.node, fmt(n.mass).c_str(), fmt(n.stiffest).c_str(),
                        fmt(n.shortest_edge).c_str(), plural(n.degree, "spring").c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(fmt(n.dt_safe).c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(fmt(n.gamma_safe).c_str());
    ImGui::TableNextColumn();
    text_wrapped(n.cause);
  }
  ImGui::EndTable();
}

}  // namespace dampbound::ui
