// dampbound suggest SCENE [--dt X | --gamma X]: stable values (docs/criteria.md).
// For a dt: the damping range every applicable criterion accepts (per node class where the
// model is non-uniform) and the fastest-settling damping in it. For a damping: the largest
// stable dt. Every suggestion is run through a Session and its outcome printed.
#include <cstdio>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "app/answer_lines.hpp"
#include "app/commands.hpp"
#include "app/options.hpp"
#include "app/suggest_knobs.hpp"
#include "app/suggest_mass.hpp"
#include "app/wait_note.hpp"
#include "core/analysis/answer.hpp"
#include "core/analysis/criteria_safe.hpp"
#include "core/analysis/damping_limits.hpp"
#include "core/analysis/equilibrium.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/shared_analysis.hpp"
#include "core/analysis/substeps.hpp"
#include "core/analysis/suggest.hpp"
#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "core/physics/integrate.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound::app::cmd_suggest {
namespace {

struct SuggestArgs {
  std::string scene;
  double factor_budget = 0, frame_dt = 0;
  int trials = 16;
  bool no_verify = false, brief = false;
  CLI::Option* frame_dt_opt = nullptr;
  ParamFlags f;  // --m --kappa --dt --gamma --zeta --integrator --max-iter --kd --rayleigh-*
  MassScaleArgs mass;  // SPEC 11: --mass-scale, or --frame-dt with --substeps
  int substeps = 0;
  CLI::Option *mass_opt = nullptr, *substeps_opt = nullptr, *mass_only[5] = {};
  bool kappa_max = false;                    // --kappa-max [--vtu FILE] (suggest_knobs.hpp)
  std::string vtu, rayleigh, band, plot;     // --rayleigh Z[,Z2] [--band F1:F2] [--plot FILE]
};

/// The nodal damping ratio of `params` on the scene's model (SPEC 10), as zeta_text() gives it.
std::string zeta_of(const SceneSpec& scene, const Params& params) {
  return zeta_text(damping_ratio_range(compile_model(scene.model, params)));
}

void print_runs(const SceneSpec& scene, const std::vector<VerifiedRun>& runs,
                const std::string& recommended) {
  if (runs.empty()) return;
  std::printf(
      "runs (the scene's perturbation and limit, policy fixed, settled rule; the suggested "
      "value must settle, the others show the range's ends)\n");
  for (const VerifiedRun& r : runs) {
    const bool judged = r.label == recommended;
    std::printf("  %-34s gamma=%-10s zeta=%-8s dt=%-10s %s%s (max |x-X| %s cm)\n",
                r.label.c_str(), format_human(r.params.gamma).c_str(),
                zeta_of(scene, r.params).c_str(), format_human(r.params.dt).c_str(),
                judged ? (r.verified() ? "verified: " : "NOT verified: ") : "",
                verdict_text(r.result, r.rules).c_str(),
                format_human(r.result.max_displacement).c_str());
  }
}

/// The run labelled `label` did not settle.
bool unverified(const std::vector<VerifiedRun>& runs, const std::string& label) {
  for (const VerifiedRun& r : runs)
    if (r.label == label && !r.verified()) return true;
  return false;
}

/// Exit 1 when the value suggested for use (the run labelled `label`) did not settle: a CI job
/// must not take it. The other runs probe the range's ends and only inform.
int recommendation_status(const std::vector<VerifiedRun>& runs, const std::string& label) {
  for (const VerifiedRun& r : runs)
    if (r.label == label && !r.verified()) {
      std::printf("not verified: the %s did not settle in its run; do not use it as is (raise "
                  "max_iterations, or take a value nearer the middle of the range)\n",
                  label.c_str());
      return 1;
    }
  return 0;
}

int print_damping(const SceneSpec& scene, const DampingSuggestion& s) {
  std::printf("damping range at dt = %s s (the user's gamma; gamma_i = gamma * gamma_scale_i)\n",
              format_human(s.dt).c_str());
  std::printf("  gamma_min  %-14s set by %s\n", format_human(s.gamma_min).c_str(), s.min_by.c_str());
  if (s.proved_only) {
    std::printf("  gamma_max  %-14s set by %s\n", format_human(s.gamma_max).c_str(),
                s.max_by.c_str());
    std::printf("  exact limits not computed: %s\n", s.exact.over_budget_reason().c_str());
    if (std::isfinite(s.gamma_unstable_from))
      std::printf("  the exact upper limit lies in [%s, %s): every gamma from %s on is proved "
                  "unstable\n",
                  format_human(s.gamma_max).c_str(),
                  format_human(s.gamma_unstable_from).c_str(),
                  format_human(s.gamma_unstable_from).c_str());
  } else {
    std::printf("  gamma_max  %-14s set by %s (exclusive)\n", format_human(s.gamma_max).c_str(),
                s.max_by.c_str());
  }
  const std::string scope = safe_bound_scope(s.exact.integrator);
  if (s.safe_max <= 0)  // some node has gamma_safe_i <= 0: SPEC 9 guarantees no gamma here
    std::printf("  safe bound no gamma: gamma_safe_i <= 0 at some node at this dt (%s)\n",
                format_human(s.safe_max).c_str());
  else if (scope.empty())
    std::printf("  safe bound gamma < %-10s guarantees stability at every node (at rest)\n",
                format_human(s.safe_max).c_str());
  else
    std::printf("  safe bound gamma < %-10s (%s)\n", format_human(s.safe_max).c_str(),
                scope.c_str());
  std::printf("  per node class (m_i, kappa_i = max incident stiffness, gamma_scale_i):\n");
  for (const NodeClass& c : s.classes) {
    std::printf("    %11s like %-5d m_i=%-10s kappa_i=%-10s scale=%-6s eq.5 %-12s gamma_i in [%s, %s%c\n",
                plural(c.count, "node").c_str(), c.example, format_human(c.mass).c_str(), format_human(c.kappa).c_str(),
                format_human(c.gamma_scale).c_str(), format_human(c.lower_bound).c_str(), format_human(c.gamma_min).c_str(),
                format_human(c.gamma_max).c_str(), s.proved_only ? ']' : ')');
    if (c.lower_bound > 0)
      std::printf("          zeta_i in [%s, %s%c\n", format_human(c.gamma_min / c.lower_bound).c_str(),
                  format_human(c.gamma_max / c.lower_bound).c_str(), s.proved_only ? ']' : ')');
    if (!scope.empty())
      std::printf("          safe bound: gamma_i < %s; at eq.5 dt < %s s (%s)\n",
                  format_human(c.safe_max).c_str(), format_human(c.dt_safe).c_str(),
                  scope.c_str());
    else if (c.lower_bound < c.safe_max)
      std::printf("          safe bound: gamma_i in [%s, %s); critical damping guaranteed "
                  "for dt < %s s\n",
                  format_human(c.lower_bound).c_str(), format_human(c.safe_max).c_str(), format_human(c.dt_safe).c_str());
    else
      std::printf("          safe bound: gamma_safe_i %s < eq.5: critical damping cannot be "
                  "guaranteed at this dt; it is for dt < %s s\n",
                  format_human(c.safe_max).c_str(), format_human(c.dt_safe).c_str());
  }
  std::printf("  dt-only criteria at this dt:");
  for (const CriterionResult& c : s.dt_only) std::printf(" %s %s;", c.name.c_str(), to_string(c.verdict));
  std::printf("\n");
  if (s.empty) {
    std::printf("no damping satisfies every criterion at this dt (gamma_min %s gamma_max)\n",
                s.proved_only ? ">" : ">=");
    std::printf("largest %s dt at gamma_min: %s s (try suggest --gamma %s)\n",
                s.proved_only ? "proved stable" : "stable",
                format_human(s.dt_max_at_gamma_min).c_str(), format_human(s.gamma_min).c_str());
    return 1;
  }
  if (!s.dt_accepted) std::printf("warning: a dt-only criterion rejects this dt whatever the damping\n");
  std::printf("fastest settling gamma  %s  (%s%s)\n", format_human(s.gamma_best).c_str(),
              s.best_method.c_str(),
              std::isnan(s.best_rho)
                  ? ""
                  : ((!s.proved_only ? "; rho = "
                      : integrator_traits(s.exact.integrator).euler_velocity_update
                          ? "; rho <= "  // the ends of the interval decide (quasi-convex)
                          : "; rho about ") +  // 65 lambdas sampled
                     format_human(s.best_rho))
                        .c_str());
  print_runs(scene, s.runs, "fastest-settling gamma");
  return recommendation_status(s.runs, "fastest-settling gamma");
}

int print_step(const SceneSpec& scene, const Params& p, const StepSuggestion& s) {
  std::printf("largest stable dt at gamma = %s (zeta = %s)\n", format_human(s.gamma).c_str(),
              zeta_of(scene, p).c_str());
  if (s.proved_only) {
    std::printf("  proved stable dt <= %s s (without a factorisation)\n", format_human(s.dt_exact).c_str());
    std::printf("  exact limit   not computed: %s\n", s.exact.over_budget_reason().c_str());
    if (std::isfinite(s.dt_unstable_from))
      std::printf("                it lies in [%s, %s): every dt from %s s on is proved unstable\n",
                  format_human(s.dt_exact).c_str(), format_human(s.dt_unstable_from).c_str(),
                  format_human(s.dt_unstable_from).c_str());
  } else {
    std::printf("  exact limit   dt < %s s (%s)\n", format_human(s.dt_exact).c_str(), to_string(s.exact.method));
  }
  std::printf("  all criteria  dt <= %s s, set by %s\n", format_human(s.dt_all).c_str(), s.dt_all_by.c_str());
  const std::string scope = safe_bound_scope(s.exact.integrator);
  if (scope.empty())
    std::printf("  safe bound dt < %s s guarantees stability at every node (at rest; node %d "
                "sets it)\n",
                format_human(s.dt_safe).c_str(), s.dt_safe_node);
  else
    std::printf("  safe bound dt < %s s (node %d sets it; %s)\n",
                format_human(s.dt_safe).c_str(), s.dt_safe_node, scope.c_str());
  // The run that checks the answer: at the largest dt every criterion accepts, or, where
  // that is the exact limit itself, the run at 99% of it (suggest_step makes only that one).
  const std::string checked = s.runs.empty() ? std::string() : s.runs.back().label;
  print_runs(scene, s.runs, checked);
  if (!(s.dt_all > 0)) return 1;  // no dt to suggest (said first: step_answer)
  return recommendation_status(s.runs, checked);
}

/// 1000000 as "1,000,000".
std::string grouped(long long n) {
  std::string digits = std::to_string(n), out;
  for (size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) out += ',';
    out += digits[k];
  }
  return out;
}

int print_substeps(const std::string& scene_arg, const SubstepSuggestion& s) {
  std::printf("substeps per frame of %s s (dt = frame / n; limits at the rest state, runs from "
              "the scene's start)\n",
              format_human(s.frame_dt).c_str());
  auto line = [&](const SubstepCount& c, const char* what) {
    if (c.n == 0) {
      // The limit unknown, or a count over the cap: say which, with the cap's dt.
      if (c.limit > 0 && std::isfinite(c.limit))
        std::printf("  %-12s no count: dt < %s s needs more than the cap of %s substeps "
                    "(frame / %s = %s s); shorten --frame-dt\n",
                    what, format_human(c.limit).c_str(), grouped(kMaxSubsteps).c_str(),
                    grouped(kMaxSubsteps).c_str(),
                    format_human(s.frame_dt / kMaxSubsteps).c_str());
      else
        std::printf("  %-12s no count (dt limit %s s)\n", what, format_human(c.limit).c_str());
      return;
    }
    std::printf("  %-12s %s: dt = %s s", what, substeps_text(c.n).c_str(),
                format_human(c.dt).c_str());
    if (c.limit > 0) std::printf(" < %s s", format_human(c.limit).c_str());
    if (c.ran)
      std::printf("; %s: %s", c.verified() ? "verified" : "NOT verified",
                  verdict_text(c.run.result, c.run.rules).c_str());
    std::printf("\n");
  };
  line(s.exact, "exact limit");
  line(s.safe, "safe bound");
  if (s.exact.ran && !s.exact.verified()) {
    if (s.by_running.n > 0) {
      if (s.search_runs > 0) line(s.by_running, "by running");
      std::printf("  %-12s the fewest that settles: %s; %s did not settle%s\n", "",
                  substeps_text(s.by_running.n).c_str(), substeps_text(s.failed_at_most).c_str(),
                  s.failed_at_most + 1 == s.by_running.n ? "" : " (not every count between was run)");
    } else if (s.search_runs > 0) {
      std::printf("  %-12s no count up to %s settled (%s)\n", "by running",
                  substeps_text(s.failed_at_most).c_str(), plural(s.search_runs, "run").c_str());
    }
  }
  if (!s.note.empty()) std::printf("  %s\n", s.note.c_str());
  if (!s.exact.ran && !s.safe.ran) return s.exact.n > 0 || s.safe.n > 0 ? 0 : 1;  // --no-verify
  if (s.answer()) return 0;  // said first (substeps_answer)
  std::printf("next         where no run diverged, the damping does not let it settle in the "
              "scene's time: dampbound suggest %s --dt %s gives the damping range\n",
              scene_arg.c_str(),
              format_human(s.exact.n > 0 ? s.exact.dt : s.frame_dt).c_str());
  return 1;
}

int run(const SuggestArgs& a) {
  WaitNote note("suggest");  // a wait over 2 s is said on stderr, stage by stage
  note.stage("reading the scene");
  SceneSpec scene = load_scene_arg(a.scene);
  Params p = scene.params;
  StopRules rules = scene.rules;
  a.f.apply(p, rules);
  resolve_zeta(scene.model, p);
  require_magnitudes(scene.model, p);
  p.policy = DampingPolicy::fixed;
  const std::string name = scene.name.empty() ? a.scene : scene.name;
  const bool json = a.mass.json && (a.mass_opt->count() || a.substeps_opt->count());
  // The evidence's head, after the answer (core/analysis/answer.hpp).
  auto head = [&] {
    if (json) return;
    std::printf("scene        %s (%s)\n", name.c_str(), scene_counts(scene.model, false).c_str());
    std::printf("parameters   m=%s kappa=%s dt=%s s integrator=%s max_iterations=%d\n",
                format_human(p.m).c_str(), format_human(p.kappa).c_str(),
                format_human(p.dt).c_str(), to_string(p.integrator), rules.max_iterations);
    const Model model = compile_model(scene.model, p);
    const NetForce n = net_force(model, model.spec().rest);
    if (!n.balanced() && !json)  // external forces, or rest lengths other than the rest geometry's
      std::printf("note         %s; these suggestions linearise at rest, which a run leaves; "
                  "bounds --equilibrium analyses where a damped run settles\n",
                  rest_not_in_equilibrium(n).c_str());
  };
  SuggestOptions options;
  options.verify = !a.no_verify;
  options.threads = 0;  // a big mesh's Lanczos products on every CPU (the same bits)
  options.trials = a.trials;
  options.max_factor_flops = a.factor_budget * 1e9;
  options.shared = std::make_shared<SharedAnalysis>();  // one spectrum for the command's analyses
  options.progress = [&note](int done, int total, const std::string& next) {
    note.stage(next, done, total);
    return true;
  };
  note.stage("exact linear analysis (" + scene_counts(scene.model, false) + ")");
  // What an answer over the budget leaves: one line naming the flag that asked and the budget.
  const auto within_budget = [](const char* flag, const std::function<int()>& answer) {
    try {
      return answer();
    } catch (const FactorisationOverBudget& over) {
      throw std::runtime_error(std::string(flag) + ": not computed: " + over.what() +
                               " (raise --factor-budget)");
    }
  };
  if (a.kappa_max) {
    head();
    return within_budget("--kappa-max", [&] {
      return print_kappa_max(scene, p, rules, !a.no_verify, a.vtu, options.max_factor_flops);
    });
  }
  if (!a.rayleigh.empty()) {
    head();
    return within_budget("--rayleigh", [&] {
      return print_rayleigh(scene, p, a.rayleigh, a.band, a.plot, options.max_factor_flops);
    });
  }
  if (a.mass_opt->count() || a.substeps_opt->count()) {
    head();
    MassScaleArgs m = a.mass;
    m.scene_arg = a.scene;
    m.verify = !a.no_verify;
    m.max_factor_flops = options.max_factor_flops;
    if (a.substeps_opt->count()) m.dt_target = a.frame_dt / a.substeps;
    return within_budget("--mass-scale", [&] { return suggest_mass_scaling(scene, p, rules, m); });
  }
  for (const CLI::Option* o : a.mass_only)
    if (o->count())
      throw InputError(o->get_name() + " goes with --mass-scale DT or --frame-dt F --substeps N");
  if (a.frame_dt_opt->count()) {
    const SubstepSuggestion s = suggest_substeps(scene, p, rules, a.frame_dt, options);
    print_answer(substeps_answer(s));
    if (a.brief)
      return s.answer() || (!s.exact.ran && !s.safe.ran && (s.exact.n > 0 || s.safe.n > 0)) ? 0 : 1;
    head();
    return print_substeps(a.scene, s);
  }
  if (a.f.gamma_opt->count() || a.f.zeta_opt->count()) {
    const StepSuggestion s = suggest_step(scene, p, rules, options);
    print_answer(step_answer(s));
    if (a.brief)
      return !(s.dt_all > 0) || unverified(s.runs, s.runs.empty() ? std::string() : s.runs.back().label) ? 1 : 0;
    head();
    return print_step(scene, p, s);
  }
  const DampingSuggestion d = suggest_damping(scene, p, rules, options);
  print_answer(damping_answer(d));
  if (a.brief) return d.empty || unverified(d.runs, "fastest-settling gamma") ? 1 : 0;
  head();
  const int status = print_damping(scene, d);
  // SPEC 10: with dashpot or Rayleigh damping in play, the range of each kind.
  const bool spec10 = p.kd != 0 || p.rayleigh_mass != 0 || p.rayleigh_stiffness != 0;
  if (spec10 && integrator_traits(p.integrator).paper_step) {
    note.stage("the stable range of each damping kind");
    print_damping_kinds(scene, p, rules, !a.no_verify, options.max_factor_flops);
  }
  return status;
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<SuggestArgs>();
  CLI::App* cmd = root.add_subcommand(
      "suggest",
      "Suggest stable values for a scene: with --dt (or the scene's dt) the damping range that "
      "every applicable criterion accepts and the fastest-settling damping in it; with --gamma "
      "the largest stable dt. Each suggestion is verified by running it. Exit 1 when no "
      "damping satisfies every criterion.");
  cmd->add_option("scene", a->scene, "scene file (.toml) or the name of a shipped scene")->required();
  a->f.m_opt = cmd->add_option("--m", a->f.m, "node mass (mass unit)")->check(finite_positive());
  a->f.kappa_opt = cmd->add_option("--kappa", a->f.kappa, "stiffness (mass unit/s^2)")->check(finite_positive());
  a->f.dt_opt = cmd->add_option("--dt", a->f.dt, "time step (s): suggest the damping")->check(finite_positive());
  a->f.gamma_opt = cmd->add_option("--gamma", a->f.gamma, "damping (mass unit/s): suggest the time step")
                     ->check(finite_non_negative());
  a->f.zeta_opt = add_zeta_option(cmd, a->f.zeta, a->f.gamma_opt);
  a->f.zeta_opt->description(a->f.zeta_opt->get_description() + ": suggest the time step");
  a->frame_dt_opt = cmd->add_option("--frame-dt", a->frame_dt,
                                    "frame time (s): the fewest substeps n with dt = frame/n "
                                    "stable by the exact limit and the n the safe bound "
                                    "guarantees (at the scene's gamma or --gamma/--zeta), each run from the "
                                    "scene's start; where the exact count does not settle, the fewest count "
                                    "that does, found by running. Exit 1 when no count is verified")
                        ->check(finite_positive());
  a->frame_dt_opt->excludes(a->f.dt_opt);
  a->f.dt_opt->excludes(a->f.gamma_opt);
  a->f.dt_opt->excludes(a->f.zeta_opt);
  a->f.integrator_opt =
      cmd->add_option("--integrator", a->f.integrator, "integrator (default: the scene's)")
          ->check(CLI::IsMember(integrator_names()));
  a->f.max_iter_opt = cmd->add_option("--max-iter", a->f.max_iter, "iteration limit of the verification runs")
                        ->check(whole_range(1, 100000000));
  cmd->add_option("--trials", a->trials, "trial runs for the best damping of a non-uniform model")
      ->check(whole_range(2, 1000));
  a->f.add_damping_to(cmd);
  // SPEC 11 (docs/criteria.md, "Mass scaling"): the least added mass for a target step.
  const MassScaleFlags mass = add_mass_scale_flags(cmd, a->mass, a->substeps, a->f.dt_opt,
                                                   a->frame_dt_opt);
  a->mass_opt = mass.target;
  a->substeps_opt = mass.substeps;
  for (int k = 0; k < 5; ++k) a->mass_only[k] = mass.only[k];
  cmd->add_flag("--no-verify", a->no_verify, "do not run the suggestions");
  add_brief_flag(cmd, a->brief);
  add_factor_budget_option(cmd, a->factor_budget);
  CLI::Option* kappa_max = cmd->add_flag(
      "--kappa-max", a->kappa_max,
      "the largest factor on every stiffness (and per region) stable at the scene's dt and "
      "damping, run at 0.98x and 1.02x, and each node's contact stiffness ceiling");
  cmd->add_option("--vtu", a->vtu, "with --kappa-max: write the rest state with the point array "
                                   "contact_stiffness_max to this .vtu")
      ->needs(kappa_max);
  CLI::Option* rayleigh = cmd->add_option(
      "--rayleigh", a->rayleigh,
      "Z or Z1,Z2: Rayleigh alpha and beta giving these damping ratios at two frequencies of "
      "the model's spectrum, checked at the scene's dt");
  cmd->add_option("--band", a->band, "with --rayleigh: F1:F2 in Hz (default: the lowest mode "
                                     "and the highest the step resolves)")
      ->needs(rayleigh);
  cmd->add_option("--plot", a->plot, "with --rayleigh: draw zeta(f) to this PNG")->needs(rayleigh);
  kappa_max->excludes(rayleigh);
  return [a] { return run(*a); };
}

const bool registered = register_command("suggest", setup);

}  // namespace
}  // namespace dampbound::app::cmd_suggest
