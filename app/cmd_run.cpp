// dampbound run SCENE: the paper's protocol on one scene (SPEC 5).
#include <cstdio>
#include <memory>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "core/io.hpp"
#include "core/report.hpp"
#include "core/session.hpp"

namespace dampbound::app {
namespace {

struct RunArgs {
  std::string scene, trace;
  bool json = false;
  ParamFlags flags;
};

int run(const RunArgs& a) {
  SceneSpec scene = load_scene_arg(a.scene);
  Params params = scene.params;
  StopRules rules = scene.rules;
  a.flags.apply(params, rules);
  if (!a.trace.empty()) check_writable(a.trace);
  Session session(std::move(scene), params, rules);
  const RunResult& r = session.run_to_end();
  if (!a.trace.empty())
    write_file_atomic(a.trace, [&](std::ostream& out) { write_trace_csv(out, session.trace()); });
  const std::string name = session.scene().name.empty() ? a.scene : session.scene().name;
  if (a.json) {
    std::printf("%s\n", result_json(name, params, rules, session.watched(), r).c_str());
    return 0;
  }
  std::printf("scene        %s (%d nodes, %d springs, %d anchors)\n", name.c_str(),
              session.model().node_count(), session.model().spring_count(),
              session.model().anchor_count());
  std::printf("parameters   m=%s kappa=%s gamma=%s dt=%s s policy=%s factor=%s integrator=%s\n",
              format_number(params.m).c_str(), format_number(params.kappa).c_str(),
              format_number(params.gamma).c_str(), format_number(params.dt).c_str(),
              to_string(params.policy), format_number(params.factor).c_str(),
              to_string(params.integrator));
  std::printf("lower bound  %s (watched node %d, eq. 5)\n",
              format_number(session.model().lower_bound[static_cast<size_t>(session.watched())])
                  .c_str(),
              session.watched());
  std::printf("outcome      %s at iteration %d (t = %s s)\n", to_string(r.outcome), r.iterations,
              format_number(r.time).c_str());
  std::printf("max |x-X|    %s cm (restore below %s cm, diverge above %s cm)\n",
              format_number(r.max_displacement).c_str(),
              format_number(rules.restore_fraction * rules.reference).c_str(),
              format_number(rules.diverge_factor * rules.reference).c_str());
  std::printf("violations   %lld node-steps, unstabilisable %lld node-steps, clamped %lld\n",
              r.violations, r.unstabilisable, r.clamped);
  if (params.policy == DampingPolicy::safe || r.unguaranteed || r.compressed_springs)
    std::printf("safe bound   critical damping not guaranteed in %lld node-steps (SPEC 9); "
                "%lld compressed spring-steps%s\n",
                r.unguaranteed, r.compressed_springs,
                r.compressed_springs ? " (K may be indefinite there: no guarantee)" : "");
  if (r.zero_length_springs)
    std::printf("warning      %lld zero-length spring evaluations contributed no force\n",
                r.zero_length_springs);
  return 0;
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<RunArgs>();
  CLI::App* cmd = root.add_subcommand(
      "run",
      "Run the paper's protocol on a scene: step until restored (max |x-X| < 1% of the "
      "perturbation), diverged (non-finite or > 100x), or the iteration limit.");
  cmd->add_option("scene", a->scene, "scene file (.toml) or the name of a shipped scene")
      ->required();
  a->flags.add_to(cmd);
  cmd->add_option("--trace", a->trace,
                  "write one CSV row per iteration (watched node's displacement in cm, bounds "
                  "and damping in mass unit/s, max displacement)");
  cmd->add_flag("--json", a->json, "print one JSON object instead of text");
  return [a] { return run(*a); };
}

const bool registered = register_command("run", setup);

}  // namespace
}  // namespace dampbound::app
