#pragma once
// Small ImGui helpers shared by the tuner's panels.
#include <imgui.h>

#include <algorithm>
#include <exception>
#include <string>
#include <string_view>

#include "dampbound/run/protocol.hpp"
#include "ui/gui_items.hpp"
#include "ui/plot.hpp"
#include "ui/text_wrap.hpp"

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

/// The colour of a run's verdict: settled (or restored) with no exit seen green, diverged red,
/// not settled / not restored amber, running the text colour; amber once it has entered the
/// band and left it (SPEC 8), even where it settled later: a run that left the band is never
/// green.
inline ImVec4 outcome_color(const RunResult& r) {
  switch (r.outcome) {
    case Outcome::settled:
    case Outcome::restored:
      return r.left_at > 0 ? gui_amber() : gui_green();
    case Outcome::diverged:
      return gui_red();
    case Outcome::not_restored:
    case Outcome::not_settled:
      return gui_amber();
    case Outcome::running:
      if (r.left_at > 0) return gui_amber();
      break;
  }
  return ImGui::GetStyle().Colors[ImGuiCol_Text];
}

/// A section title: a little space, the label in the header colour, a separator.
inline void section_header(const char* label) {
  ImGui::Spacing();
  {
    const ScopedStyleColor header(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_PlotHistogram]);
    ImGui::TextUnformatted(label);
  }
  ImGui::Separator();
}

/// `text` wrapped to the space left on the line, broken at blanks only (ui/text_wrap.hpp:
/// ImGui's TextWrapped would split a number after its '.'), at most kShownText bytes of it.
/// One item, for IsItemHovered.
inline void text_wrapped(std::string_view text) {
  const float width = std::max(ImGui::GetContentRegionAvail().x, 1.0f);
  const std::string lines = wrap_at_blanks(shorten(text, kShownText), width, [](std::string_view s) {
    return ImGui::CalcTextSize(s.data(), s.data() + s.size()).x;
  });
  ImGui::TextUnformatted(lines.data(), lines.data() + lines.size());
}

/// A tooltip whose lines are wrapped at blanks to at most half the window's width (and 40
/// em), so that ImGui can keep it on screen: a formula or a long test no longer runs off it.
inline void wrapped_tooltip(std::string_view text) {
  const ImGuiIO& io = ImGui::GetIO();
  const float width = std::max(std::min(40.0f * ImGui::GetFontSize(), 0.5f * io.DisplaySize.x),
                               8.0f * ImGui::GetFontSize());
  std::string lines;
  size_t start = 0;
  while (start <= text.size()) {  // each given line wrapped on its own
    const size_t end = std::min(text.find('\n', start), text.size());
    if (!lines.empty()) lines += '\n';
    lines += wrap_at_blanks(text.substr(start, end - start), width, [](std::string_view s) {
      return ImGui::CalcTextSize(s.data(), s.data() + s.size()).x;
    });
    start = end + 1;
  }
  ImGui::BeginTooltip();
  ImGui::TextUnformatted(lines.data(), lines.data() + lines.size());
  ImGui::EndTooltip();
}

/// Wrapped text in `color`.
inline void wrapped_colored(const ImVec4& color, std::string_view text) {
  const ScopedStyleColor coloured(ImGuiCol_Text, color);
  text_wrapped(text);
}

/// SameLine() when an item `width` pixels wide still fits on the current line of the window,
/// else nothing (the item goes to the next line): toolbars that wrap in small windows.
inline void same_line_if_fits(float width) {
  const float end = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  if (end - ImGui::GetItemRectMax().x - ImGui::GetStyle().ItemSpacing.x >= width) ImGui::SameLine();
}

/// The width of a checkbox with `label` (pixels).
inline float checkbox_width(const char* label) {
  return ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x +
         ImGui::CalcTextSize(label).x;
}

/// The dark plot style with a transparent data area: the window colour shows through, and a
/// software rasteriser is spared the fill.
inline PlotStyle gui_plot_style() {
  PlotStyle s = plot_style_dark();
  s.plot_background = 0;
  return s;
}

/// The one-line result of a button's action (Export, Save): what it did, or why it failed.
struct ActionMessage {
  std::string text;
  bool failed = false;
  /// Runs `action` (returning the summary line); an exception's message becomes the text.
  template <class Action>
  void run(Action&& action) {
    try {
      text = action();
      failed = false;
    } catch (const std::exception& e) {
      text = e.what();
      failed = true;
    }
  }
  /// The text, green or red, wrapped; nothing before the first run.
  void show() const {
    if (!text.empty()) wrapped_colored(failed ? gui_red() : gui_green(), text.c_str());
  }
};

}  // namespace dampbound::ui
