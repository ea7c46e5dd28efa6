// The tuner's "Save scene" tab: the current scene, its parameters and the pinned runs written
// as a scene file whose [[expect]] tables `dampbound check` replays (ui/tuner_save.hpp).
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "ui/gui_app.hpp"
#include "ui/gui_items.hpp"
#include "ui/gui_widgets.hpp"

namespace dampbound::ui {

std::string GuiApp::save_scene(const std::string& path, std::vector<std::string>* notes) {
  return save_tuner_scene(*tuner_, path, save_.tolerance, notes);
}

void GuiApp::save_panel() {
  Tuner& t = *tuner_;
  int runs = 0;
  for (const Pin& p : t.pins()) runs += p.scene == t.scene().name;
  text_wrapped("Writes the scene with the current parameters as [params], each of its " +
               std::to_string(runs) +
               " pinned runs as a [[run]], and what each run measured as an [[expect]] entry: "
               "`dampbound check FILE` replays them headless.");
  section_header("Tolerances of the [[expect]] entries");
  const float w = std::min(ImGui::GetContentRegionAvail().x * 0.45f, 160.0f);
  ImGui::SetNextItemWidth(w);
  if (item::input_int("+- iterations", &save_.tolerance.iterations, 1, 10))
    save_.tolerance.iterations = std::max(0, save_.tolerance.iterations);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Each asserted iteration may move this far, or 5 %% of it if more");
  ImGui::SetNextItemWidth(w);
  double f = save_.tolerance.displacement_factor;
  if (item::input_double("x final displacement", &f, 0.1, 1.0, "%.2f"))
    save_.tolerance.displacement_factor = std::clamp(f, 1.0, 1e6);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "max_displacement_below = this x the measured final max displacement\n"
        "(1 = not asserted; diverged runs never)");
  item::checkbox("assert the node-step counts", &save_.tolerance.counts);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("violations_max and unstabilisable_max = the measured node-steps");
  section_header("File");
  if (save_.path.empty())
    save_.path = (t.scene().name.empty() ? std::string("tuned") : t.scene().name) + "-tuned.toml";
  const float bw = ImGui::CalcTextSize("Save").x + ImGui::GetStyle().FramePadding.x * 2;
  ImGui::SetNextItemWidth(-bw - ImGui::GetStyle().ItemSpacing.x);
  item::input_text_hint("##save_path", "scene file (.toml)", &save_.path);
  ImGui::SameLine();
  if (item::button("Save")) {
    save_.notes.clear();
    save_.result.run([&] { return save_scene(save_.path, &save_.notes); });
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Runs changed by hand (dragged, cut, a parameter changed mid-run) or still running\n"
        "are replayed headless first: the file holds what `check` will measure.");
  save_.result.show();
  for (const std::string& n : save_.notes) wrapped_colored(gui_amber(), n.c_str());
}

}  // namespace dampbound::ui
