#pragma once
// Small ImGui helpers shared by the tuner's panels.
#include <imgui.h>

#include "core/protocol.hpp"

namespace dampbound::ui {

/// Colours of verdicts and warnings in the panels (dark theme).
inline ImVec4 gui_red() {
  return ImVec4(1.0f, 0.42f, 0.38f, 1.0f);
}
inline ImVec4 gui_amber() {
  return ImVec4(1.0f, 0.75f, 0.3f, 1.0f);
}
inline ImVec4 gui_green() {
  return ImVec4(0.45f, 0.85f, 0.5f, 1.0f);
}

/// The colour of a run's verdict: restored green, diverged red, not restored amber, running
/// the text colour.
inline ImVec4 outcome_color(Outcome o) {
  switch (o) {
    case Outcome::restored:
      return gui_green();
    case Outcome::diverged:
      return gui_red();
    case Outcome::not_restored:
      return gui_amber();
    case Outcome::running:
      break;
  }
  return ImGui::GetStyle().Colors[ImGuiCol_Text];
}

/// A section title: a little space, the label in the header colour, a separator.
inline void section_header(const char* label) {
  ImGui::Spacing();
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_PlotHistogram]);
  ImGui::TextUnformatted(label);
  ImGui::PopStyleColor();
  ImGui::Separator();
}

/// Wrapped text in `color`.
inline void wrapped_colored(const ImVec4& color, const char* text) {
  ImGui::PushStyleColor(ImGuiCol_Text, color);
  ImGui::TextWrapped("%s", text);
  ImGui::PopStyleColor();
}

/// SameLine() when an item `width` pixels wide still fits on the current line of the window,
/// else nothing (the item goes to the next line): toolbars that wrap in small windows.
inline void same_line_if_fits(float width) {
  const float end = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  if (end - ImGui::GetItemRectMax().x - ImGui::GetStyle().ItemSpacing.x >= width)
    ImGui::SameLine();
}

/// The width of a checkbox with `label` (pixels).
inline float checkbox_width(const char* label) {
  return ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x +
         ImGui::CalcTextSize(label).x;
}

}  // namespace dampbound::ui
