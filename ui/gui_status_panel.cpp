// The tuner's "Status", "Runs" (pins and export) and plot windows.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <string>

#include "core/io/report.hpp"
#include "core/physics/damping_ratio.hpp"
#include "ui/gui_app.hpp"
#include "ui/gui_export.hpp"
#include "ui/gui_items.hpp"
#include "ui/gui_widgets.hpp"
#include "ui/mesh_style.hpp"
#include "ui/plot.hpp"
#include "ui/tuner_export.hpp"

namespace dampbound::ui {

namespace {

/// One "label | value" row of a two-column table.
void row(const char* label, const std::string& value, const ImVec4* color = nullptr) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextDisabled("%s", label);
  ImGui::TableNextColumn();
  const ScopedStyleColor coloured(ImGuiCol_Text, color != nullptr ? *color : ImVec4(), color != nullptr);
  text_wrapped(value);
}

}  // namespace

void GuiApp::status_panel() {
  const Session& s = tuner_->session();
  const Model& m = s.model();
  const RunResult& r = s.result();
  const StopRules& rules = s.rules();
  const StepSample* last = s.trace().empty() ? nullptr : &s.trace().back();
  if (ImGui::BeginTable("status", 2, ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("k", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("v", ImGuiTableColumnFlags_WidthStretch);
    row("scene", shorten(s.scene().name, kShownName));
    row("mesh", plural(m.spec().node_count(), "node") + ", " + plural(m.spec().spring_count(), "spring") +
                    (s.springs_cut() > 0 ? " (" + std::to_string(s.springs_cut()) + " cut)" : ""));
    row("iteration",
        std::to_string(s.state().iteration) + "   (t = " + fmt(s.state().time) + " s)");
    const ImVec4 oc = outcome_color(r);
    row("outcome", verdict_short(r), &oc);
    // SPEC 8: the band history, so a run that entered and left is read as such.
    const auto at = [](int it) { return it > 0 ? std::to_string(it) : std::string("-"); };
    row("first entry", at(r.first_entry) + " (the paper's restored)");
    row("exit", at(r.left_at), r.left_at > 0 ? &oc : nullptr);
    row("settled", r.outcome == Outcome::settled
                       ? at(r.settled_at)
                       : r.outcome == Outcome::running && r.below_since > 0
                             ? "below since " + at(r.below_since) + ", until the limit " +
                                   std::to_string(rules.max_iterations) + "?"
                             : std::string("-"));
    row("divergence", r.outcome == Outcome::diverged ? at(r.iterations) : std::string("-"));
    const double thr = rules.restore_fraction * rules.reference;
    // The state as it is now: at the perturbed start, after a drag or a perturbation, the
    // last step's numbers are not it.
    row("max |x - X|", fmt(tuner_->max_displacement_now()) + " cm (band < " + fmt(thr) + ")");
    const int w = s.watched();
    const NodeStatus ns = w < static_cast<int>(s.workspace().status.size())
                              ? s.workspace().status[static_cast<size_t>(w)]
                              : NodeStatus::within;
    const ImVec4 wc = ImGui::ColorConvertU32ToFloat4(status_color(ns));
    row("watched node", "#" + std::to_string(w) + ", " + status_label(ns), &wc);
    row("  |x - X|", fmt(tuner_->watched_displacement_now()) + " cm");
    if (last != nullptr) {
      row("  bounds", fmt(last->watched.lower) + " .. " + fmt(last->watched.upper));
      row("  gamma",
          fmt(last->watched.gamma) + " (effective " + fmt(last->watched.gamma_eff) + ")");
      // SPEC 10: the ratio beside the gamma it is of (zeta_i = gamma_i / 2 sqrt(m_i kappa_i)).
      row(u8"  \u03B6 zeta", fmt(damping_ratio(last->watched.gamma, last->watched.lower)) +
                              " (effective " +
                              fmt(damping_ratio(last->watched.gamma_eff, last->watched.lower)) + ")");
    }
    const ImVec4 amber = gui_amber();
    auto count_row = [&](const char* label, int now, long long total, bool warn_if_any) {
      row(label, std::to_string(now) + " now, " + std::to_string(total) + " node-steps",
          warn_if_any && now > 0 ? &amber : nullptr);
    };
    count_row("violating", last ? last->violating : 0, r.violations, true);
    count_row("unstabilisable", last ? last->unstabilisable : 0, r.unstabilisable, true);
    count_row("clamped", last ? last->clamped : 0, r.clamped, false);
    const GuiStats& st = meter_.stats();
    row("frame", fmt(st.frame_ms) + " ms (" + fmt(st.frame_ms > 0 ? 1000.0 / st.frame_ms : 0.0) +
                     " fps)");
    row("speed", tuner_->playing() ? fmt(st.steps_per_second) + " steps/s" : std::string("paused"));
    const Tuner::BudgetCut cut = tuner_->budget_cut();
    if (cut.asked > 0) {  // the frame budget binds: fewer steps than the slider asks
      const ImVec4 binds = gui_amber();
      row("  budget", std::to_string(cut.taken) + " of " + std::to_string(cut.asked) +
                          " steps per frame (each frame steps at most " +
                          fmt(tuner_->playback().frame_budget_seconds * 1e3) + " ms)",
          &binds);
    }
    ImGui::EndTable();
  }
  if (!tuner_->notice().empty()) {
    const bool bad = r.outcome == Outcome::diverged || !warnings_.empty();
    wrapped_colored(bad ? gui_red() : gui_amber(), tuner_->notice().c_str());
  }
  if (item::small_button("Reset layout")) layout_.request_reset();
}

void GuiApp::runs_panel() {
  Tuner& t = *tuner_;
  const float pin_w = ImGui::CalcTextSize("Pin run").x + ImGui::GetStyle().FramePadding.x * 2;
  ImGui::SetNextItemWidth(-pin_w - ImGui::GetStyle().ItemSpacing.x);
  const std::string hint = params_label(t.params());
  item::input_text_hint("##pin_name", hint.c_str(), &runs_.pin_name);
  ImGui::SameLine();
  if (item::button("Pin run")) {
    t.pin(runs_.pin_name);
    runs_.pin_name.clear();
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Keep the current run's traces on the plots under this name\n"
        "(its parameters when left empty)");
  int remove = -1;
  const ImGuiTableFlags tf = ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_ScrollY;
  const float table_h =
      ImGui::GetContentRegionAvail().y - 3.4f * ImGui::GetFrameHeightWithSpacing();
  if (!t.pins().empty() && ImGui::BeginTable("pins", 4, tf, ImVec2(0, std::max(table_h, 60.0f)))) {
    ImGui::TableSetupColumn("show", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("name", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableSetupColumn("outcome", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("x", ImGuiTableColumnFlags_WidthFixed);
    for (size_t i = 0; i < t.pins().size(); ++i) {
      Pin& p = t.pins()[i];
      const ScopedID row_id(static_cast<int>(i));
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      {
        const ScopedStyleColor mark(ImGuiCol_CheckMark, p.color);
        item::checkbox("##visible", &p.visible);
      }
      ImGui::TableNextColumn();
      ImGui::SetNextItemWidth(-1.0f);
      {
        const ScopedStyleColor coloured(ImGuiCol_Text, p.color);
        item::input_text("##name", &p.name);
      }
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s\n%s", verdict_short(p.result).c_str(), params_label(p.params).c_str());
      ImGui::TableNextColumn();
      const ImVec4 oc = outcome_color(p.result);
      ImGui::TextColored(oc, "%s", verdict_short(p.result).c_str());
      ImGui::TableNextColumn();
      if (item::small_button("x")) remove = static_cast<int>(i);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Remove this pin");
    }
    ImGui::EndTable();
  } else if (t.pins().empty()) {
    ImGui::TextDisabled("No pinned runs: pin one to compare it with the next.");
  }
  if (remove >= 0) t.unpin(static_cast<size_t>(remove));
  section_header("Export plots (PNG) and data (CSV)");
  const float half = (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) * 0.5f;
  ImGui::SetNextItemWidth(half);
  item::input_text_hint("##dir", "folder (default: here)", &runs_.export_dir);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1.0f);
  item::input_text_hint("##prefix", "file prefix", &runs_.export_prefix);
  if (item::button("Export"))
    runs_.export_result.run([&] { return export_plots(runs_.export_dir, runs_.export_prefix); });
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Writes PREFIX_plots.png, PREFIX_traces.csv (one row per run and\n"
        "iteration) and PREFIX_runs.csv (one row per run), each atomically");
  same_line_if_fits(checkbox_width("unfinished current run"));
  item::checkbox("unfinished current run", &runs_.export_unfinished);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Export the current run before its verdict too (it is always\n"
        "exported once it reached the limit, settled or diverged)");
  if (!runs_.export_result.text.empty()) ImGui::SameLine();
  runs_.export_result.show();
}

std::string GuiApp::export_plots(const std::string& dir, const std::string& prefix) {
  const bool current = export_includes_current(*tuner_, runs_.export_unfinished);
  return export_runs(*tuner_, export_plot_specs(*tuner_, plot_options_, current), dir, prefix,
                     current);
}

void GuiApp::plots_envelope() {
  const PlotSpec spec = tuner_envelope_plot(*tuner_, plot_options_);
  plot_widget("envelope", spec, ImVec2(-1.0f, -1.0f), gui_plot_style());
}

void GuiApp::plots_displacement() {
  item::checkbox("log10 y axis", &plot_options_.log_y);
  same_line_if_fits(checkbox_width("max over all nodes"));
  item::checkbox("max over all nodes", &plot_options_.show_max);
  same_line_if_fits(checkbox_width("pinned runs"));
  item::checkbox("pinned runs", &plot_options_.show_pins);
  const PlotSpec spec = tuner_displacement_plot(*tuner_, plot_options_);
  plot_widget("displacement", spec, ImVec2(-1.0f, -1.0f), gui_plot_style());
}

}  // namespace dampbound::ui
