// The Suggest tab's stiffness ceiling and Rayleigh pair (ui/tuner_knobs.hpp): a ratio field, a
// button that computes both on a worker thread (progress and Cancel as Suggest has), the
// answers with their runs, and apply buttons.
#include <imgui.h>

#include <cmath>
#include <string>

#include "core/io/report.hpp"
#include "core/physics/integrate.hpp"
#include "ui/gui_app.hpp"
#include "ui/gui_items.hpp"
#include "ui/gui_job_status.hpp"
#include "ui/gui_widgets.hpp"

namespace dampbound::ui {

namespace {

void knob_run_line(const char* what, const VerifiedRun& r) {
  ImGui::BulletText("%s:", what);
  ImGui::SameLine();
  ImGui::TextColored(outcome_color(r.result), "%s", verdict_short(r.result).c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s\n%s\nthe perturbation and the band scaled to the linear regime",
                      r.label.c_str(), params_label(r.params).c_str());
}

void ceiling_lines(const KnobsResult& r) {
  const StiffnessCeiling& c = r.ceiling;
  if (!r.ceiling_error.empty()) {
    wrapped_colored(gui_amber(), "stiffness ceiling: " + r.ceiling_error);
    return;
  }
  if (std::isinf(c.factor)) {
    text_wrapped("stiffness ceiling: none (no spring or anchor acts on a free node)");
    return;
  }
  if (!(c.factor > 0)) {
    wrapped_colored(gui_amber(), "stiffness ceiling: unstable even without the springs (index " +
                                     fmt(c.index) + " >= 4 at kappa)");
    return;
  }
  text_wrapped("stiffness ceiling: kappa x " + fmt(c.factor) + " = " +
               fmt(c.factor * r.params.kappa) + " (every spring and anchor; index " +
               fmt(c.index) + " of 4 at kappa)");
  if (ImGui::IsItemHovered())
    wrapped_tooltip("The largest factor on every stiffness that keeps the step stable at this "
                    "dt and damping (SPEC 10's exact index at rest, certified; beta K follows "
                    "the stiffness; gamma held), as dampbound suggest --kappa-max prints it.");
  if (c.ran) {
    knob_run_line("run at 0.98 x", c.below);
    knob_run_line("run at 1.02 x", c.above);
  }
}

void rayleigh_lines(const KnobsResult& r) {
  if (!r.rayleigh) {
    wrapped_colored(gui_amber(), "Rayleigh pair: " + r.rayleigh_error);
    return;
  }
  const RayleighDesign& d = *r.rayleigh;
  text_wrapped("Rayleigh pair for zeta " + fmt(d.zeta1) + " at " + fmt(d.f1) + " Hz and " +
               fmt(d.f2) + " Hz: alpha = " + fmt(d.alpha) + " 1/s, beta = " + fmt(d.beta) + " s");
  if (ImGui::IsItemHovered())
    wrapped_tooltip("From the spectrum of M^-1 K at rest: lowest mode " + fmt(d.f_lowest) +
                    " Hz, highest " + fmt(d.f_highest) + " Hz; the step resolves up to " +
                    fmt(d.f_nyquist) + " Hz. zeta(f) = alpha / (4 pi f) + beta pi f; as "
                    "dampbound suggest --rayleigh prints it.");
  if (!d.feasible) {
    wrapped_colored(gui_amber(), std::string("no Rayleigh pair gives these ratios (") +
                                     (d.alpha < 0 ? "alpha" : "beta") + " would be negative)");
  } else if (d.stable) {
    ImGui::TextColored(gui_green(), "stable at this dt (beta < %s s); dt limit %s s",
                       fmt(d.beta_max).c_str(), fmt(d.dt_max).c_str());
  } else {
    wrapped_colored(gui_red(), "NOT stable at this dt: the largest stable beta is " +
                                   fmt(d.beta_max) + " s (zeta " + fmt(d.zeta2_at_beta_max) +
                                   " at " + fmt(d.f2) + " Hz); dt limit with the pair " +
                                   fmt(d.dt_max) + " s");
  }
}

}  // namespace

void GuiApp::knobs_section() {
  Tuner& t = *tuner_;
  section_header("Stiffness ceiling and Rayleigh pair");
  BackgroundJob<KnobsResult>& job = knobs_.job();
  ImGui::SetNextItemWidth(ImGui::CalcTextSize("0.0500000").x * 1.6f);
  double z = rayleigh_zeta_;
  if (item::input_double("zeta##rayleigh", &z, 0, 0, "%.4g") && !number_problem(z, false))
    rayleigh_zeta_ = z;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The damping ratio the Rayleigh pair gives the lowest mode and the\n"
                      "highest mode the step resolves (default 0.05)");
  ImGui::SameLine();
  {
    const ScopedDisabled off(job.busy());
    if (item::button("Ceiling and pair")) start_knobs();
  }
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "The largest factor on every stiffness that keeps this dt stable (runs at 0.98x and\n"
        "1.02x of it), and the Rayleigh alpha, beta giving zeta at both ends of the\n"
        "spectrum, judged at this dt; for the mesh as it is now (with its cuts).");
  job_status(job, "Cancel##knobs");
  if (!job.result()) return;
  const KnobsResult& r = *job.result();
  if (r.springs_cut > 0) ImGui::TextDisabled("for the mesh as cut (%d springs cut)", r.springs_cut);
  ceiling_lines(r);
  if (!integrator_traits(r.params.integrator).paper_step) {
    // Both answers are the paper's step's: one click to it, and they are computed again.
    if (item::small_button("use the paper's step##knobs")) {
      Params p = t.params();
      p.integrator = Integrator::semi_implicit_euler;
      if (t.set_params(p)) start_knobs();
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Switch the integrator to semi-implicit Euler (the paper's step) and\n"
                        "compute the ceiling and the pair for it");
    return;
  }
  if (const auto p = with_kappa_ceiling(t.params(), r)) {
    const std::string label = "apply kappa = " + fmt(p->kappa) + "##ceiling";
    if (item::small_button(label.c_str())) {
      // The ceiling holds gamma: zeta mode would move gamma with kappa.
      if (t.zeta_mode()) t.set_zeta_mode(false);
      t.set_params(*p);
      t.set_notice("kappa = " + fmt(p->kappa) + ": 0.98 x the stiffness ceiling (gamma held)");
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("kappa = 0.98 x %s x %s: 2%% below the ceiling, where its run went\n"
                        "(gamma held: zeta mode turns off)",
                        fmt(r.ceiling.factor).c_str(), fmt(r.params.kappa).c_str());
  }
  rayleigh_lines(r);
  if (const auto p = with_rayleigh_pair(t.params(), r)) {
    if (item::small_button("apply alpha, beta")) t.set_params(*p);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("rayleigh_mass = %s 1/s, rayleigh_stiffness = %s s (their sliders on)",
                        fmt(p->rayleigh_mass).c_str(), fmt(p->rayleigh_stiffness).c_str());
  }
}

}  // namespace dampbound::ui
