#pragma once
// The line a background computation shows while it runs (Suggest, the substeps, the stiffness
// ceiling and the Rayleigh pair): Cancel, the seconds so far and the stage it is at.
#include <imgui.h>

#include <string>

#include "ui/background_job.hpp"
#include "ui/gui_items.hpp"
#include "ui/gui_widgets.hpp"
#include "ui/tuner.hpp"

namespace dampbound::ui {

/// Busy: Cancel, the seconds so far and the stage; else "cancelled" after a Cancel; the error.
/// `cancel`: the Cancel button's label ("Cancel", with an ## identity where a window has two).
template <class T>
inline void job_status(BackgroundJob<T>& job, const char* cancel = "Cancel") {
  if (job.busy()) {
    ImGui::SameLine();
    if (item::small_button(cancel)) job.cancel();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Drop this computation (the last result stays)");
    ImGui::SameLine();
    ImGui::TextDisabled("computing and verifying... %s s", fmt(job.seconds()).c_str());
    const std::string where = job.progress();
    if (!where.empty())
      wrapped_colored(ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled), where);
  } else if (job.cancelled()) {
    ImGui::SameLine();
    ImGui::TextDisabled("cancelled");
  }
  if (!job.error().empty()) wrapped_colored(gui_red(), job.error().c_str());
}


}  // namespace dampbound::ui
