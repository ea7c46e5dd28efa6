// The Suggest tab's alternative to substeps (SPEC 11): "or add X% mass to N nodes" so that one
// step per frame is stable, with its run, an apply button that switches the live model to the
// scaled masses, and the mesh coloured by the added mass.
#include <imgui.h>

#include <string>

#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "ui/gui_app.hpp"
#include "ui/gui_items.hpp"
#include "ui/gui_widgets.hpp"

namespace dampbound::ui {

void GuiApp::mass_scaling_section(const SubstepsResult& r) {
  if (!r.mass_error.empty()) ImGui::TextDisabled("%s", r.mass_error.c_str());
  if (!r.mass) return;
  const SceneMassScaling& m = *r.mass;
  const MassScalingResult& a = m.result;
  const std::string percent = format_digits(100 * a.added_fraction(), 3) + "%";
  if (a.kind == MassScalingCase::no_mass_helps) {
    ImGui::TextDisabled("no mass helps: Rayleigh alpha alone is unstable at dt = F (needs F < %s s)",
                        fmt(a.dt_no_mass).c_str());
    return;
  }
  if (a.kind != MassScalingCase::scaled) return;
  if (a.over_cap) {
    text_wrapped("or add mass: " + percent + " of the free mass, over the " +
                 format_digits(100 * a.cap, 3) + "% cap (largest dt within it " + fmt(a.dt_cap) +
                 " s); not offered");
  } else {
    text_wrapped("or add " + percent + " mass to " + std::to_string(a.scaled_count) + " node" +
                 (a.scaled_count == 1 ? "" : "s") + ": one step per frame (dt = " +
                 fmt(a.dt_target) + " s), exact limit " + fmt(a.dt_limit) + " s");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("SPEC 11: the local rule (every row of 4M - 2 dt C - dt^2 K dominant)\n"
                        "adds %s%% to %d nodes; the exact index shrinks it to %s\n"
                        "(s* = %s), designed for dt / %s.",
                        format_digits(100 * a.added_local_fraction(), 3).c_str(),
                        a.scaled_count, percent.c_str(), fmt(a.s_star).c_str(),
                        fmt(a.safety).c_str());
    if (item::small_button("apply mass##mass")) {
      tuner_->set_scene(m.scene);
      tuner_->set_notice("Masses scaled for dt = " + fmt(a.dt_target) + " s (SPEC 11): +" +
                         percent + " on " + std::to_string(a.scaled_count) + " nodes");
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Switch the model to the scaled masses at dt = %s s (the run restarts)",
                        fmt(a.dt_target).c_str());
    if (m.ran) {
      ImGui::SameLine();
      ImGui::TextColored(outcome_color(m.run.result), "run: %s",
                         verdict_short(m.run.result).c_str());
    }
  }
  bool colour = !mesh_.shade.empty();
  if (item::checkbox("colour nodes by added mass", &colour)) {
    mesh_.shade = colour ? added_mass_shade(m) : std::vector<float>{};
    ++mesh_.shade_version;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Grey: no mass added; violet to yellow: up to the most added (%s)",
                      fmt(m.top.empty() ? 0.0 : m.top.front().after - m.top.front().before).c_str());
}

}  // namespace dampbound::ui
