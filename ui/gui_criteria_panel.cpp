// The tuner's "Criteria" tab (every stability criterion, live) and "Suggest" tab (stable
// values from core/analysis/suggest.hpp, verified by runs, with buttons to apply them).
#include <imgui.h>

#include <optional>
#include <string>
#include <vector>

#include "core/io/report.hpp"
#include "ui/gui_app.hpp"
#include "ui/gui_items.hpp"
#include "ui/gui_job_status.hpp"
#include "ui/gui_widgets.hpp"

namespace dampbound::ui {

namespace {

ImVec4 verdict_color(CriterionVerdict v) {
  switch (v) {
    case CriterionVerdict::within:
      return gui_green();
    case CriterionVerdict::beyond:
      return gui_red();
    case CriterionVerdict::not_applicable:
      break;
  }
  return ImGui::GetStyle().Colors[ImGuiCol_TextDisabled];
}

void run_line(const VerifiedRun& r) {
  const ImVec4 c = outcome_color(r.result);
  ImGui::BulletText("%s:", r.label.c_str());
  ImGui::SameLine();
  ImGui::TextColored(c, "%s", verdict_short(r.result).c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s\nmax |x - X| = %s cm", params_label(r.params).c_str(),
                      fmt(r.result.max_displacement).c_str());
}

/// A row's test as the table shows it. Over the factorisation budget every exact row begins
/// with the same reason, which the line above the table gives once: the row keeps the rest.
std::string shown_test(const CriterionResult& r, const std::string& over_budget) {
  if (over_budget.empty() || r.test.rfind(over_budget, 0) != 0) return r.test;
  std::string rest = r.test.substr(over_budget.size());
  if (rest.rfind("; ", 0) == 0) rest.erase(0, 2);
  return rest.empty() ? "not computed" : rest;
}

/// "exact analysis unavailable", with the reason where the tuner leaves it out by design.
std::string unavailable(Tuner& t) {
  const std::string why = exact_not_computed_reason(t.session().model(), t.params());
  return "exact analysis unavailable" + (why.empty() ? std::string() : ": " + why);
}

}  // namespace

void GuiApp::criteria_progress(TunerCriteria& c) {
  // The analysis on the worker thread: what it does, for how long, the last one's duration
  // as the estimate, and Cancel (the last result stays on show).
  if (c.computing()) {
    if (item::small_button("Cancel##criteria")) c.cancel();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Drop this analysis (the last result stays); a change of the\n"
                        "parameters, the springs or where to linearise starts a new one");
    ImGui::SameLine();
    std::string line = "computing " + c.computing_stage() + ": " + fmt(c.computing_seconds()) + " s";
    if (c.last_seconds() > 0) line += " (the last one took " + fmt(c.last_seconds()) + " s)";
    wrapped_colored(ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled), line);
  } else if (c.cancelled()) {
    wrapped_colored(ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled),
                    "exact analysis cancelled: a change of the parameters, the springs or where "
                    "to linearise starts it again");
  }
}

void GuiApp::criteria_panel() {
  Tuner& t = *tuner_;
  const std::vector<CriterionResult>& rows = t.criteria();
  TunerCriteria& c = t.criteria_state();
  static const char* const kAt[] = {"rest", "the current state", "the static equilibrium"};
  int at = static_cast<int>(c.linearisation());
  ImGui::SetNextItemWidth(ImGui::CalcTextSize(kAt[2]).x + 2 * ImGui::GetFrameHeight());
  if (item::combo("linearise at", &at, kAt, 3))
    c.set_linearisation(static_cast<Linearisation>(at));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Where the exact analysis linearises the forces: at rest, at the current\n"
        "positions (it follows the run, refreshed every 0.2 s or so), or at the static\n"
        "equilibrium under the scene's loads and rest lengths, where a damped run settles\n"
        "(Newton's method first, as dampbound bounds --equilibrium).");
  const ExactStability* e = t.exact();
  const Equilibrium* held = c.exact_equilibrium();
  const std::string where = c.exact_at_rest() ? std::string("at rest")
                            : held != nullptr
                                ? "at the static equilibrium (" + equilibrium_summary(*held) + ")"
                                : "at iteration " + std::to_string(c.exact_iteration());
  std::optional<ScopedStyleColor> grey(std::in_place, ImGuiCol_Text,
                                       ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  // On a large mesh the rows follow a playing run every 0.2 s: say when they are behind it.
  const int now = t.session().state().iteration, rows_at = c.rows_iteration();
  const std::string behind =
      rows_at == now ? "" : " (the run is at " + std::to_string(now) + ")";
  // Before the first result arrives there is no analysis to place at rest or at a state.
  const bool over = e != nullptr && !e->computed();
  const std::string over_budget = over ? over_budget_test(*e) : std::string();
  const std::string method =
      over
          ? over_budget +
                "; its rows say what Lanczos, Gershgorin, the node-block splitting and a patch "
                "around the top prove without a factorisation"
      : e != nullptr ? std::string(to_string(e->method))
                     : std::string();
  const std::string exact =
      e != nullptr ? "exact analysis " + where + " (" + method + ")" +
                         (c.computing() ? "; computing a new one" : "")
                   : c.computing() ? std::string("exact analysis: computing")
                                   : unavailable(t);
  text_wrapped("at iteration " + std::to_string(rows_at) + behind + "; " + exact);
  grey.reset();
  criteria_progress(c);
  if (const NetForce* n = c.rest_net_force(); n != nullptr && !n->balanced())
    wrapped_colored(gui_amber(),
                    (rest_not_in_equilibrium(*n) +
                     "; a run leaves it: linearise at the static equilibrium to analyse where "
                     "a damped run settles.")
                        .c_str());
  if (c.linearisation() == Linearisation::equilibrium && !c.equilibrium_failure().empty())
    wrapped_colored(
        gui_amber(),
        ("No analysis at the static equilibrium: " + c.equilibrium_failure() + ".").c_str());
  const ImGuiTableFlags tf = ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_ScrollY |
                             ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH;
  // A narrow panel (the default layout's is about 390 px) shows one line per criterion, its
  // test on hover: with the test wrapped beside it the exact-analysis rows fell below the fold.
  const bool wide = ImGui::GetContentRegionAvail().x >= 34.0f * ImGui::GetFontSize();
  if (!ImGui::BeginTable("criteria", wide ? 3 : 2, tf)) return;
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableSetupColumn("criterion", ImGuiTableColumnFlags_WidthStretch, 1.0f);
  ImGui::TableSetupColumn("verdict", ImGuiTableColumnFlags_WidthFixed);
  if (wide) ImGui::TableSetupColumn("test", ImGuiTableColumnFlags_WidthStretch, 1.6f);
  ImGui::TableHeadersRow();
  for (const CriterionResult& r : rows) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    if (wide) {
      text_wrapped(r.name);
    } else {
      const float w = ImGui::GetContentRegionAvail().x;
      std::string base = r.name, name = r.name;  // shortened with "..." (UTF-8 safe)
      while (base.size() > 1 && ImGui::CalcTextSize(name.c_str()).x > w) {
        base.pop_back();
        while (!base.empty() && (static_cast<unsigned char>(base.back()) & 0xC0) == 0x80)
          base.pop_back();
        name = base + "...";
      }
      ImGui::TextUnformatted(name.c_str());
    }
    const std::string test = shown_test(r, over_budget);
    if (ImGui::IsItemHovered())
      wrapped_tooltip((wide ? r.name : test) + "\n" + r.formula + "\n" + r.source +
                      "\nvalue: " + fmt(r.value) + " " + r.unit);
    ImGui::TableNextColumn();
    ImGui::TextColored(verdict_color(r.verdict), "%s", to_string(r.verdict));
    if (!wide && ImGui::IsItemHovered()) wrapped_tooltip(test);
    if (wide) {
      ImGui::TableNextColumn();
      text_wrapped(test);
    }
  }
  criteria_rows_hidden_ = ImGui::GetScrollMaxY() > 0.0f;
  ImGui::EndTable();
}

void GuiApp::suggest_panel() {
  substeps_section();
  knobs_section();
  suggest_values();
}

void GuiApp::substeps_section() {
  Tuner& t = *tuner_;
  section_header("Substeps per frame");
  BackgroundJob<SubstepsResult>& job = substeps_.job();
  ImGui::SetNextItemWidth(ImGui::CalcTextSize("0.0166667").x * 1.6f);
  double f = frame_dt_;
  if (item::input_double("frame (s)", &f, 0, 0, "%.6g") && !number_problem(f, false))
    frame_dt_ = f;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The frame time F (s): dt = F/n with n substeps (default 1/60 s)");
  ImGui::SameLine();
  {
    const ScopedDisabled off(job.busy());
    if (item::button("Substeps")) start_substeps();
  }
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "The fewest substeps n with dt = F/n stable by the exact limit, and the n the\n"
        "safe bound guarantees, at this gamma and the rest state; each run from the\n"
        "mesh as it is now (with the cuts made so far). Where the exact count\n"
        "does not settle, the fewest count that does is searched for by running.");
  job_status(job, "Cancel##substeps");
  if (!job.result()) return;
  const SubstepsResult& r = *job.result();
  const SubstepSuggestion& s = r.substeps;
  if (r.springs_cut > 0) ImGui::TextDisabled("for the mesh as cut (%d springs cut)", r.springs_cut);
  struct Row {
    const SubstepCount* count;
    const char* what;
    const char* apply;
  };
  std::vector<Row> rows = {{&s.exact, "exact limit", "apply dt = F/n##exact"},
                           {&s.safe, "safe bound", "apply dt = F/n##safe"}};
  if (s.search_runs > 0 && s.by_running.n > 0)
    rows.push_back({&s.by_running, "by running", "apply dt = F/n##running"});
  for (const Row& row : rows) {
    const SubstepCount* c = row.count;
    if (c->n == 0) {
      ImGui::TextDisabled("%s: no count (limit %s s)", row.what, fmt(c->limit).c_str());
      continue;
    }
    std::string text =
        std::string(row.what) + ": " + substeps_text(c->n) + ", dt = " + fmt(c->dt) + " s";
    if (c->limit > 0) text += " < " + fmt(c->limit) + " s";
    text_wrapped(text);
    if (item::small_button(row.apply)) t.set_params(with_substeps(t.params(), *c));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Set dt = %s / %d = %s s", fmt(s.frame_dt).c_str(), c->n,
                        fmt(c->dt).c_str());
    if (c->ran) {  // the verifying run's verdict (SPEC 8)
      ImGui::SameLine();
      ImGui::TextColored(outcome_color(c->run.result), "run: %s",
                         verdict_short(c->run.result).c_str());
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s\n%s\nmax |x - X| = %s cm", c->run.label.c_str(),
                          params_label(c->run.params).c_str(),
                          fmt(c->run.result.max_displacement).c_str());
    }
  }
  if (s.exact.ran && !s.exact.verified() && (s.search_runs > 0 || s.by_running.n > 0))
    wrapped_colored(gui_amber(),
                    (s.by_running.n > 0
                         ? "The exact count did not settle (the run passes through states "
                           "stiffer than rest): " +
                               substeps_text(s.failed_at_most) + " did not settle, " +
                               std::to_string(s.by_running.n) + " did."
                         : "No count up to " + substeps_text(s.failed_at_most) +
                               " settled; where none diverged, the damping does not let it "
                               "settle in the scene's time.")
                        .c_str());
  if (const SubstepCount* use = s.answer())
    ImGui::Text("use %d substep%s per frame (dt = %s s)", use->n, use->n == 1 ? "" : "s",
                fmt(use->dt).c_str());
  if (!s.note.empty()) wrapped_colored(gui_amber(), s.note.c_str());
  mass_scaling_section(r);
  const Params& now = t.params();
  if (r.params.gamma != now.gamma || r.params.m != now.m || r.params.kappa != now.kappa ||
      s.frame_dt != frame_dt_)
    ImGui::TextDisabled("(computed for frame %s s, gamma %s)", fmt(s.frame_dt).c_str(),
                        fmt(r.params.gamma).c_str());
}

void GuiApp::suggest_values() {
  Tuner& t = *tuner_;
  section_header("Stable values");
  {
    const ScopedDisabled off(suggest_.busy());
    if (item::button("Suggest stable values")) start_suggest();
  }
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "The damping range every criterion accepts at this dt, the fastest-settling\n"
        "gamma in it, and the largest stable dt at this gamma; each verified by a\n"
        "run of the mesh as it is now (with the cuts made so far).");
  job_status(suggest_.job());
  if (!suggest_.result()) return;
  const Suggestion& s = *suggest_.result();
  const DampingSuggestion& d = s.damping;
  if (s.springs_cut > 0)
    ImGui::TextDisabled("for the mesh as cut: %s, %d cut away", plural(s.springs, "spring").c_str(), s.springs_cut);
  section_header(("Damping at dt = " + fmt(d.dt) + " s").c_str());
  if (d.empty) {
    wrapped_colored(gui_amber(), ("No damping satisfies every criterion at this dt (" + d.min_by +
                                  " vs " + d.max_by + ").")
                                     .c_str());
    ImGui::Text("largest dt stable at gamma %s: %s s", fmt(d.gamma_min).c_str(),
                fmt(d.dt_max_at_gamma_min).c_str());
  } else {
    text_wrapped("range [" + fmt(d.gamma_min) + ", " + fmt(d.gamma_max) + (d.proved_only ? "]" : ")"));
    {
      const ScopedStyleColor grey(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
      text_wrapped("from " + d.min_by + "; to " + d.max_by);
      if (d.proved_only)
        text_wrapped("exact limits not computed (over the factorisation budget); the exact upper "
                     "limit lies in [" + fmt(d.gamma_max) + ", " + fmt(d.gamma_unstable_from) + ")");
    }
    ImGui::Text("fastest settling: gamma = %s", fmt(d.gamma_best).c_str());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s (spectral radius %s)", d.best_method.c_str(), fmt(d.best_rho).c_str());
    if (item::small_button("apply gamma")) t.set_params(with_best_gamma(t.params(), s));
    ImGui::SameLine();
    if (item::small_button("apply range min")) {
      Params p = t.params();
      p.gamma = d.gamma_min;
      t.set_params(p);
    }
  }
  for (const VerifiedRun& r : d.runs) run_line(r);
  const StepSuggestion& st = s.step;
  section_header(("Time step at gamma = " + fmt(st.gamma)).c_str());
  if (st.proved_only)
    text_wrapped("largest dt proved stable without a factorisation: " + fmt(st.dt_exact) +
                 " s (the exact limit lies in [" + fmt(st.dt_exact) + ", " +
                 fmt(st.dt_unstable_from) + "))");
  else
    text_wrapped("largest stable dt (exact): " + fmt(st.dt_exact) + " s");
  text_wrapped("every criterion accepts dt <= " + fmt(st.dt_all) + " s (" + st.dt_all_by + ")");
  if (item::small_button("apply dt")) t.set_params(with_suggested_dt(t.params(), s));
  for (const VerifiedRun& r : st.runs) run_line(r);
  if (s.params.gamma != t.params().gamma || s.params.dt != t.params().dt ||
      s.params.m != t.params().m || s.params.kappa != t.params().kappa)
    ImGui::TextDisabled("(computed for %s)", params_label(s.params).c_str());
}

}  // namespace dampbound::ui
