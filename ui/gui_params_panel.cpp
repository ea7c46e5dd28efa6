// The tuner's "Parameters" window: scene picker, the parameter sliders (logarithmic, Ctrl+click
// to type), the damping policy, and playback.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include "core/io/scene_file.hpp"
#include "core/physics/damping_ratio.hpp"
#include "dampbound/physics/bounds.hpp"
#include "ui/gui_app.hpp"
#include "ui/gui_items.hpp"
#include "ui/gui_widgets.hpp"

namespace dampbound::ui {

namespace {

/// A logarithmic slider of a double with a tooltip; Ctrl+click types a value (not clamped,
/// so any value the core accepts can be entered).
bool log_slider(const char* label, double* v, double lo, double hi, const char* help) {
  const bool changed =
      item::slider_double(label, v, lo, hi, "%.5g",
                          ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_NoRoundToFormat);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s\nCtrl+click to type a value.", help);
  return changed;
}

bool key_pressed(ImGuiKey key) {
  return ImGui::IsKeyPressed(ImGui::GetKeyIndex(key), false);
}

}  // namespace

void GuiApp::open_scene(const std::string& path) {
  std::string err;
  if (tuner_->open_scene(path, &err)) {
    scene_.path = scene_.typed = path;
    scene_.error.clear();
  } else {
    scene_.error = err;
  }
}

void GuiApp::scene_picker() {
  ImGui::SetNextItemWidth(-1.0f);
  const std::string preview = scene_.path.empty()
                                  ? shorten(tuner_->scene().name, kShownName)
                                  : std::filesystem::path(scene_.path).stem().string();
  if (item::begin_combo("##scene", preview.c_str())) {
    for (const std::string& f : scene_.files) {
      const std::string stem = std::filesystem::path(f).stem().string();
      if (item::selectable(stem.c_str(), f == scene_.path)) open_scene(f);
    }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The scenes of the source tree (scenes/*.toml).");
  const float open_w = ImGui::CalcTextSize("Open").x + ImGui::GetStyle().FramePadding.x * 2;
  ImGui::SetNextItemWidth(-open_w - ImGui::GetStyle().ItemSpacing.x);
  const bool enter = item::input_text_hint("##path", "scene file (.toml) or name", &scene_.typed,
                                              ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if (item::button("Open") || enter) open_scene(resolve_scene(scene_.typed, options_.scenes_dir));
  if (!scene_.error.empty()) wrapped_colored(gui_red(), scene_.error.c_str());
  if (!tuner_->scene().description.empty()) {
    const ScopedStyleColor grey(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    text_wrapped(shorten(tuner_->scene().description, kShownDescription));
  }
}

void GuiApp::playback_controls() {
  Tuner& t = *tuner_;
  const bool can = t.can_step();
  const ImGuiIO& io = ImGui::GetIO();
  const bool keys = !io.WantCaptureKeyboard;
  const float bw = (ImGui::GetContentRegionAvail().x - 3 * ImGui::GetStyle().ItemSpacing.x) / 4;
  {
  const ScopedDisabled off(!can);
  if (item::button(t.playing() ? "Pause" : "Play", ImVec2(bw, 0)) ||
      (keys && key_pressed(ImGuiKey_Space)))
    t.set_playing(!t.playing());
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("Space");
  ImGui::SameLine();
  if (item::button("Step", ImVec2(bw, 0))) t.step(1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("One step of the paper's integrator");
  }
  ImGui::SameLine();
  if (item::button("Reset", ImVec2(bw, 0))) t.reset();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("Back to the scene's perturbed start (cuts undone), same parameters");
  ImGui::SameLine();
  if (item::button("Perturb", ImVec2(bw, 0))) t.perturb();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Apply the scene's perturbation again, now");
  int spf = t.playback().steps_per_frame;
  ImGui::SetNextItemWidth(-ImGui::CalcTextSize("steps / frame").x -
                          ImGui::GetStyle().ItemInnerSpacing.x);
  if (item::slider_int("steps / frame", &spf, 1, 1000, "%d", ImGuiSliderFlags_Logarithmic))
    t.playback().steps_per_frame = std::max(1, std::min(spf, 10000));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Steps per drawn frame, fewer where they would take over %.0f ms: the speed "
                      "line says the steps per second reached",
                      t.playback().frame_budget_seconds * 1e3);
  item::checkbox("pause at the verdict", &t.playback().pause_at_verdict);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Pause at the verdict: the iteration limit, a divergence, or the settled rule's proof "
        "(docs/settled.md)");
}

void GuiApp::damping_input(Params& p, bool& changed) {
  Tuner& t = *tuner_;
  bool zeta_on = t.zeta_mode();
  if (item::checkbox(u8"as ratio \u03B6", &zeta_on)) {
    t.set_zeta_mode(zeta_on);
    p = t.params();
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Off: the slider sets gamma. On: it sets the damping ratio zeta,\n"
                      "each node's gamma_i = zeta 2 sqrt(m_i kappa_i), kept when m or kappa move.\n"
                      "On a scene whose nodes have their own lower bounds the run restarts once.");
  ImGui::SameLine();
  if (t.zeta_mode())
    ImGui::TextDisabled(u8"\u03B3 = %s", fmt(p.gamma).c_str());
  else
    ImGui::TextDisabled(u8"\u03B6 = %s", zeta_text(t.session().model()).c_str());
  if (t.zeta_mode()) {
    double z = t.zeta();
    if (log_slider(u8"\u03B6 zeta", &z, 1e-3, 100.0,
                   "The damping ratio zeta: gamma_i = zeta 2 sqrt(m_i kappa_i) at each node")) {
      p.gamma = gamma_of_zeta(z, p);
      changed = true;
    }
  } else {
    changed |= log_slider(u8"\u03B3 gamma", &p.gamma, 1e-6, 10.0,
                          "The user's viscous damping gamma (mass unit / s)");
  }
}

void GuiApp::other_damping_input(Params& p, bool& changed) {
  // SPEC 10: dashpots along the springs and Rayleigh damping, each off (0) by default; the
  // slider keeps its last value while off.
  struct Kind {
    const char* on_id;
    const char* label;
    double Params::*member;
    double lo, hi;
    const char* help;
  };
  static constexpr Kind kinds[] = {
      {"##kd_on", "kd dashpot", &Params::kd, 1e-6, 10.0,
       "Dashpot along each spring and anchor, kd (mass unit / s):\n"
       "force kd ((v_j - v_i) . d) d on node i (Warp's spring_kd, SOFA's spring damping)"},
      {"##alpha_on", u8"\u03B1 Rayleigh M", &Params::rayleigh_mass, 1e-4, 100.0,
       "Rayleigh mass damping alpha (1/s): force -alpha m_i v_i\n(SOFA's rayleighMass)"},
      {"##beta_on", u8"\u03B2 Rayleigh K", &Params::rayleigh_stiffness, 1e-6, 1.0,
       "Rayleigh stiffness damping beta (s): force -beta (K(x) v)_i\n"
       "(SOFA's rayleighStiffness)"},
  };
  for (size_t k = 0; k < 3; ++k) {
    const Kind& kind = kinds[k];
    double& value = p.*kind.member;
    double& kept = other_damping_[k];
    bool on = value != 0;
    if (on) kept = value;
    if (item::checkbox(kind.on_id, &on)) {
      value = on ? kept : 0.0;
      changed = true;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s\nOff: 0.", kind.help);
    ImGui::SameLine(0, ImGui::GetStyle().ItemInnerSpacing.x);
    const ScopedDisabled off(!on);
    double v = on ? value : kept;
    if (log_slider(kind.label, &v, kind.lo, kind.hi, kind.help) && on) {
      value = kept = v;
      changed = true;
    }
  }
}

void GuiApp::parameters_panel() {
  Tuner& t = *tuner_;
  section_header("Scene");
  scene_picker();
  section_header("Parameters");
  Params p = t.params();
  const float label_w =
      ImGui::CalcTextSize("factor x upper").x + ImGui::GetStyle().ItemInnerSpacing.x;
  std::optional<ScopedItemWidth> width(std::in_place, -label_w);
  bool changed = false;
  changed |= log_slider("m", &p.m, 1e-5, 10.0, "Node mass m (mass unit)");
  changed |= log_slider(u8"\u03BA kappa", &p.kappa, 1e-5, 100.0,
                        "Spring and anchor stiffness kappa (mass unit / s^2)");
  damping_input(p, changed);
  // The lower bound (eq. 5) at every node: on a non-uniform mesh the worst node speaks.
  const LowerBoundCheck lb = check_lower_bound(t.session().model());
  const double lo = lower_bound(p.m, p.kappa);
  // Per-node masses or stiffnesses (mesh geometry, regions) give per-node bounds (SPEC 3).
  const bool per_node = lb.worst >= 0 && (!lb.uniform || std::abs(lb.lower - lo) > 1e-12 * lo);
  if (!per_node)
    ImGui::Text(u8"lower bound 2\u221A(m\u03BA) = %s", fmt(lo).c_str());
  else
    ImGui::Text(u8"lower bound at worst node #%d = %s", lb.worst, fmt(lb.lower).c_str());
  const char* set_lower = u8"\u03B3 = lower bound";
  const float button_w = ImGui::CalcTextSize(set_lower).x + 2 * ImGui::GetStyle().FramePadding.x;
  if (ImGui::GetContentRegionAvail().x - ImGui::GetItemRectSize().x >
      button_w + ImGui::GetStyle().ItemSpacing.x)
    ImGui::SameLine();  // beside the value when there is room, else below it
  if (item::small_button(set_lower)) {
    // The smallest gamma that puts every node at or above its bound.
    p.gamma = per_node && lb.ratio > 0 ? p.gamma / lb.ratio : lo;
    changed = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Set gamma so that every node's gamma_i >= 2 sqrt(m_i kappa_i) (paper eq. 5),\n"
                      "the worst node exactly at its bound");
  const std::string worst =
      lb.uniform ? "" : " (worst node #" + std::to_string(lb.worst) + ": " + fmt(lb.ratio) + " x)";
  if (lb.worst < 0) {
    ImGui::TextDisabled("no node has a lower bound");
  } else if (std::abs(lb.ratio - 1.0) < 1e-9) {
    wrapped_colored(gui_green(), (u8"\u03B3 at the lower bound: critical damping" + worst).c_str());
  } else if (lb.below > 0) {
    const std::string where = lb.uniform ? "" : " at " + std::to_string(lb.below) + " of " +
                                                    plural(lb.nodes, "node");
    wrapped_colored(gui_amber(), (u8"\u03B3 below the lower bound" + where +
                                  (lb.uniform ? " (" + fmt(lb.ratio) + " x)" : worst) +
                                  ": underdamped").c_str());
  } else {
    wrapped_colored(gui_green(), (u8"\u03B3 above the lower bound" +
                                  (lb.uniform ? " (" + fmt(lb.ratio) + " x)" : " at every node" + worst))
                                     .c_str());
  }
  changed |= log_slider("dt (s)", &p.dt, 1e-4, 1.0, "Time step dt (s)");
  other_damping_input(p, changed);
  int policy = 0;
  while (kPolicies[policy] != p.policy) ++policy;
  auto policy_name = [](void*, int k, const char** out) {
    *out = to_string(kPolicies[k]);
    return true;
  };
  if (item::combo("policy", &policy, policy_name, nullptr, IM_ARRAYSIZE(kPolicies))) {
    p.policy = kPolicies[policy];
    changed = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Effective damping each step (paper sec. 5):\n"
        "fixed: gamma as given\nclamp: gamma clamped into [lower, upper]\n"
        "upper: factor x upper bound (eq. 6)\nlower: the lower bound (eq. 5)\n"
        "safe: gamma clamped into [lower, safe bound]: stability of the\n"
        "paper's semi-implicit step guaranteed (not derived for the other integrators)");
  {
    const ScopedDisabled off(p.policy != DampingPolicy::upper);
    changed |= item::slider_double("factor x upper", &p.factor, 0.0, 2.0, "%.3f");
  }
  int integ = static_cast<int>(p.integrator);
  const char* integrators[] = {"semi-implicit Euler (paper)", "forward Euler", "Verlet", "RK4",
                               "implicit Euler"};
  if (item::combo("integrator", &integ, integrators, 5)) {
    p.integrator = static_cast<Integrator>(integ);
    changed = true;
  }
  int max_iter = t.session().rules().max_iterations;
  if (item::input_int("max iterations", &max_iter, 100, 1000)) t.set_max_iterations(max_iter);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The iteration limit: the settled rule gives its verdict here");
  width.reset();
  if (changed) {
    std::string err;
    if (t.set_params(p, &err)) {
      param_error_.clear();
    } else {
      param_error_ = "not applied: " + err;
    }
  }
  if (!param_error_.empty()) {
    wrapped_colored(gui_red(), param_error_.c_str());
  }
  section_header("Playback");
  playback_controls();
}

}  // namespace dampbound::ui
