// dampbound run SCENE: one scene judged by the settled rule (SPEC 8) or the paper's (SPEC 5).
#include <cstdio>
#include <memory>

#include "app/answer_lines.hpp"
#include "app/commands.hpp"
#include "app/options.hpp"
#include "app/wait_note.hpp"
#include "core/analysis/answer.hpp"
#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "core/io/vtu.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound::app::cmd_run {
namespace {

struct RunArgs {
  std::string scene, trace;
  std::string rule = "settled";  // SPEC 8: a user's question is whether it stays stable
  std::string vtk;               // ParaView series folder (core/io/vtu.hpp)
  int every = 1;
  bool json = false, verbose = false, brief = false;
  int threads = 1;
  ParamFlags flags;
};

int run(const RunArgs& a) {
  SceneSpec scene = load_scene_arg(a.scene);
  Params params = scene.params;
  StopRules rules = scene.rules;
  a.flags.apply(params, rules);
  resolve_zeta(scene.model, params);
  require_magnitudes(scene.model, params);
  rules.rule = stop_rule_of(a.rule);
  if (!a.trace.empty()) check_writable(a.trace);
  Session session(std::move(scene), params, rules);
  session.set_keep_trace(!a.trace.empty());  // without --trace, memory stays flat
  session.set_threads(a.threads);
  // A run over 2 s says its iteration on stderr (Ctrl-C ends it with one line).
  WaitNote note("run", a.vtk.empty() ? "nothing was written"
                                     : "the .vtu files saved so far are kept, without series.pvd");
  const int limit = rules.max_iterations;
  note.stage("stepping", 0, limit);
  std::unique_ptr<VtuSeries> vtk;
  StepObserver save;
  if (!a.vtk.empty()) {
    // Iteration 0, every N-th step and the last one; the .pvd lists them with their times.
    vtk = std::make_unique<VtuSeries>(a.vtk, session.scene().body);
    vtk->set_parameters(session.params());
    vtk->add(session.model(), session.state(), session.workspace(), session.params().dt);
    save = [&](const StepSample& st) {
      if (st.iteration % a.every == 0 || !session.running())
        vtk->add(session.model(), session.state(), session.workspace(), session.params().dt);
    };
  }
  const RunResult& r = session.run_to_end([&](const StepSample& st) {
    if (st.iteration % 64 == 0) note.stage("stepping", st.iteration, limit);
    if (save) save(st);
  });
  note.stage("writing the outputs");
  if (vtk) vtk->write_collection();
  if (!a.trace.empty())
    write_file_atomic(a.trace, [&](std::ostream& out) { write_trace_csv(out, session.trace()); });
  const std::string name = session.scene().name.empty() ? a.scene : session.scene().name;
  const DampingRatioRange zeta = damping_ratio_range(session.model());
  if (a.json) {
    std::printf("%s\n", result_json(name, params, rules, session.watched(), r, &zeta).c_str());
    return 0;
  }
  print_answer(run_answer(r, rules, params));  // the verdict and what to try, first
  if (a.brief) return 0;
  std::printf("scene        %s (%s)\n", name.c_str(), scene_counts(session.model().spec()).c_str());
  std::printf("parameters   m=%s kappa=%s gamma=%s (zeta=%s) dt=%s s policy=%s integrator=%s\n",
              format_human(params.m).c_str(), format_human(params.kappa).c_str(),
              format_human(params.gamma).c_str(), zeta_text(zeta).c_str(),
              format_human(params.dt).c_str(), to_string(params.policy),
              to_string(params.integrator));
  if (params.kd != 0 || params.rayleigh_mass != 0 || params.rayleigh_stiffness != 0)
    std::printf("damping      kd=%s rayleigh_mass=%s 1/s rayleigh_stiffness=%s s\n",
                format_human(params.kd).c_str(), format_human(params.rayleigh_mass).c_str(),
                format_human(params.rayleigh_stiffness).c_str());
  std::printf("max |x-X|    %s cm at the end (the band: below %s cm; diverged: above %s cm)\n",
              format_human(r.max_displacement).c_str(),
              format_human(rules.restore_fraction * rules.reference).c_str(),
              format_human(rules.diverge_factor * rules.reference).c_str());
  if (r.outcome == Outcome::diverged || r.outcome == Outcome::not_settled ||
      r.outcome == Outcome::not_restored)
    std::printf("next         dampbound suggest %s gives the damping range at this dt and the "
                "largest stable dt at this gamma\n",
                a.scene.c_str());
  if (r.zero_length_springs)
    std::printf("warning      %lld zero-length spring evaluations contributed no force: give "
                "those springs a direction (distinct node positions)\n",
                r.zero_length_springs);
  if (!a.verbose) return 0;
  // The paper's counts, for those who study them (docs/criteria.md says what each means).
  std::printf("lower bound  %s at the watched node %d (eq. 5)\n",
              format_human(session.model().lower_bound[static_cast<size_t>(session.watched())])
                  .c_str(),
              session.watched());
  std::printf("node-steps   %lld outside [eq. 5, eq. 6], %lld where eq. 5 > eq. 6 (no damping "
              "meets both), %lld clamped by the policy\n",
              r.violations, r.unstabilisable, r.clamped);
  std::printf("safe bound   %lld node-steps where critical damping was not guaranteed; %lld "
              "spring-steps in compression (no guarantee there)\n",
              r.unguaranteed, r.compressed_springs);
  return 0;
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<RunArgs>();
  CLI::App* cmd = root.add_subcommand(
      "run",
      "Run a scene and judge it: under the settled rule (default) step to the iteration limit "
      "and say whether max |x-X| stayed below 1% of the perturbation from some iteration on; "
      "under --rule first-entry (the paper's protocol) stop at the first entry below it. "
      "Either way a divergence (non-finite or > 100x) ends the run.");
  cmd->add_option("scene", a->scene, "scene file (.toml) or the name of a shipped scene")
      ->required();
  a->flags.add_to(cmd);
  add_rule_option(cmd, a->rule, "default: settled");
  cmd->add_option("--trace", a->trace,
                  "write one CSV row per iteration (watched node's displacement in cm, bounds "
                  "and damping in mass unit/s, max displacement)");
  cmd->add_flag("--json", a->json, "print one JSON object instead of text");
  add_brief_flag(cmd, a->brief);
  cmd->add_flag("--verbose", a->verbose,
                "also print the paper's per-step counts (violations of eq. 5 and 6, "
                "unstabilisable and clamped node-steps, the safe bound's)");
  cmd->add_option("--vtk", a->vtk,
                  "write a ParaView series to this folder: step_NNNNNN.vtu (nodes with "
                  "displacement, velocity, bounds, damping, state; springs with stiffness, "
                  "strain) and series.pvd");
  cmd->add_option("--every", a->every, "with --vtk: save every N-th step (and the last)")
      ->check(whole_range(1, 100000000));
  cmd->add_option("--threads", a->threads,
                  "threads for each step's node loops (0 = one per hardware thread); the "
                  "results are the same bits on any count")
      ->check(whole_range(0, 1024));
  return [a] { return run(*a); };
}

const bool registered = register_command("run", setup);

}  // namespace
}  // namespace dampbound::app::cmd_run
