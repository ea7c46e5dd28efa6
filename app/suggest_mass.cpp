// suggest --mass-scale: SPEC 11's answer as text, JSON, a scaled scene and a .vtu.
#include "app/suggest_mass.hpp"

#include "app/options.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "core/analysis/mass_scaling_scene.hpp"
#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "core/io/scene_file.hpp"
#include "core/io/scene_write.hpp"
#include "core/io/vtu.hpp"
#include "core/physics/integrate.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound::app::suggest_mass {
namespace {

std::string percent(double fraction) { return format_digits(100 * fraction, 3) + "%"; }

/// An exact dt limit, certified to 1e-5 relative (IndexCertifier::dt_limit): 5 digits.
std::string limit(double dt) { return format_digits(dt, 5); }

/// Writes the scaled scene and reads it back: the masses must come back bit for bit.
void write_scene(const SceneMassScaling& s, const MassScaleArgs& a) {
  const std::vector<std::string> header = {
      "Written by dampbound suggest " + a.scene_arg + " --mass-scale " +
          format_number(a.dt_target) + " --safety " + format_number(a.safety) + " (SPEC 11):",
      "the masses that make dt* = " + format_number(a.dt_target) +
          " s stable, at that dt with the fixed policy."};
  write_file_atomic(a.write_scene,
                    [&](std::ostream& out) { write_scene_toml(out, s.scene, a.write_scene, header); });
  const SceneSpec back = load_scene(a.write_scene);
  const Model m0 = compile_model(s.scene.model, s.scene.params),
              m1 = compile_model(back.model, back.params);
  if (!same_topology(back.model, s.scene.model) || m0.mass != m1.mass || m0.gamma != m1.gamma ||
      m0.spring_kd != m1.spring_kd || m0.anchor_kd != m1.anchor_kd)
    throw std::runtime_error(a.write_scene + ": the scene written does not read back to the "
                             "same model; please report it");
}

void write_vtk(const SceneMassScaling& s, const std::string& path) {
  const Model model = compile_model(s.scene.model, s.scene.params);
  State rest;  // the scaled model at rest
  rest.x = model.spec().rest;
  rest.v.assign(rest.x.size(), Vec3::Zero());
  std::vector<double> added(s.mass_after.size());
  for (size_t i = 0; i < added.size(); ++i) added[i] = s.mass_after[i] - s.mass_before[i];
  write_file_atomic(path, [&](std::ostream& out) {
    write_vtu(out, model, rest, StepWorkspace{}, s.params.dt, s.scene.body,
              {{"added_mass", added}, {"mass_before", s.mass_before}});
  });
}

void print_json(const SceneSpec& scene, const SceneMassScaling& s) {
  const MassScalingResult& r = s.result;
  std::string top;
  for (const ScaledNode& n : s.top)
    top += std::string(top.empty() ? "" : ",") + "{\"node\":" + std::to_string(n.node) +
           ",\"before\":" + json_number(n.before) + ",\"after\":" + json_number(n.after) +
           ",\"factor\":" + json_number(n.factor) + ",\"cause\":" + json_string(n.cause) + "}";
  std::printf(
      "{\"scene\":%s,\"answer\":%s,\"dt_target\":%s,\"safety\":%s,\"dt_design\":%s,"
      "\"free_mass\":%s,\"dt_limit_before\":%s,\"dt_no_mass\":%s,\"scaled_nodes\":%d,"
      "\"added_local\":%s,\"added\":%s,\"added_local_percent\":%s,\"added_percent\":%s,"
      "\"s_star\":%s,\"dt_limit\":%s,\"frequency_before\":%s,\"frequency_after\":%s,"
      "\"frequency_change_percent\":%s,\"lower_bound_change_percent\":%s,"
      "\"lower_bound_node\":%d,\"cap_percent\":%s,\"over_cap\":%s,\"dt_cap\":%s,"
      "\"dt_cap_added_percent\":%s,\"factorizations\":%d,\"run\":%s,\"top\":[%s]}\n",
      json_string(scene.name).c_str(), json_string(to_string(r.kind)).c_str(),
      json_number(r.dt_target).c_str(), json_number(r.safety).c_str(),
      json_number(r.dt_design).c_str(), json_number(r.free_mass).c_str(),
      json_number(r.dt_limit_before).c_str(), json_number(r.dt_no_mass).c_str(), r.scaled_count,
      json_number(r.added_local).c_str(), json_number(r.added).c_str(),
      json_number(100 * r.added_local_fraction()).c_str(),
      json_number(100 * r.added_fraction()).c_str(), json_number(r.s_star).c_str(),
      json_number(r.dt_limit).c_str(), json_number(s.frequency_before).c_str(),
      json_number(s.frequency_after).c_str(), json_number(s.frequency_change).c_str(),
      json_number(s.lower_bound_change).c_str(), s.lower_bound_node,
      json_number(100 * r.cap).c_str(), r.over_cap ? "true" : "false",
      json_number(r.dt_cap).c_str(),
      json_number(r.free_mass > 0 ? 100 * r.dt_cap_added / r.free_mass : 0).c_str(),
      r.factorizations,
      s.ran ? json_string(verdict_short(s.run.result)).c_str() : "null", top.c_str());
}

void print_report(const SceneMassScaling& s) {
  const MassScalingResult& r = s.result;
  std::printf("  local rule   +%s (%s of the free mass %s), %d node%s scaled: every row of "
              "4M - 2 dt_g C - dt_g^2 K dominant (guaranteed)\n",
              format_human(r.added_local).c_str(), percent(r.added_local_fraction()).c_str(),
              format_human(r.free_mass).c_str(), r.scaled_count, r.scaled_count == 1 ? "" : "s");
  std::printf("  tightened    +%s (%s), s* = %s along the local rule's masses: the exact index "
              "certified below 4%s\n",
              format_human(r.added).c_str(), percent(r.added_fraction()).c_str(),
              format_digits(r.s_star, 4).c_str(),
              r.local_certified ? "" : " (the local rule itself was not certified: rounding)");
  std::printf("  scaled model exact dt limit %s s (dt_g %s s)\n", limit(r.dt_limit).c_str(),
              format_human(r.dt_design).c_str());
  std::printf("  lowest frequency sqrt(lambda_min(M^-1 K)) %s -> %s 1/s (%s%%)\n",
              format_human(s.frequency_before).c_str(), format_human(s.frequency_after).c_str(),
              format_digits(s.frequency_change, 3).c_str());
  if (s.lower_bound_node >= 0)
    std::printf("  lower bound eq. 5 grows by at most %s%% (node %d)\n",
                format_digits(s.lower_bound_change, 3).c_str(), s.lower_bound_node);
  std::printf("  %zu node%s with the most added mass:\n     node  mass before  mass after   "
              "factor   cause\n",
              s.top.size(), s.top.size() == 1 ? "" : "s");
  for (const ScaledNode& n : s.top)
    std::printf("  %7d  %-11s  %-11s  %-7s  %s\n", n.node, format_digits(n.before, 5).c_str(),
                format_digits(n.after, 5).c_str(), format_digits(n.factor, 4).c_str(),
                n.cause.c_str());
}

}  // namespace
}  // namespace dampbound::app::suggest_mass

namespace dampbound::app {

int suggest_mass_scaling(const SceneSpec& scene, const Params& params, const StopRules& rules,
                         const MassScaleArgs& a) {
  if (!integrator_traits(params.integrator).paper_step)
    throw InputError("--mass-scale analyses the paper's step (semi-implicit Euler), not " +
                     std::string(to_string(params.integrator)));
  SceneMassScalingOptions o;
  o.safety = a.safety;
  o.max_added = a.max_added / 100;
  o.verify = a.verify;
  o.max_factor_flops = a.max_factor_flops;
  const auto start = std::chrono::steady_clock::now();
  o.progress = [start](const std::string& next) {  // stderr, once a call has taken 2 s
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (t > 2) std::fprintf(stderr, "mass scaling: %s (%.1f s so far)\n", next.c_str(), t);
    return true;
  };
  const SceneMassScaling s = scene_mass_scaling(scene, params, rules, a.dt_target, o);
  const MassScalingResult& r = s.result;
  const bool scaled = r.kind == MassScalingCase::scaled;
  using namespace suggest_mass;
  if (!a.write_scene.empty() && r.kind != MassScalingCase::no_mass_helps) write_scene(s, a);
  if (!a.vtk.empty() && r.kind != MassScalingCase::no_mass_helps) write_vtk(s, a.vtk);
  const bool run_ok = !s.ran || s.run.verified();
  const int status = r.kind == MassScalingCase::no_mass_helps || r.over_cap || !run_ok ? 1 : 0;
  if (a.json) {
    print_json(scene, s);
    return status;
  }
  std::printf("mass scaling for dt* = %s s (safety %s: designed for dt_g = %s s; SPEC 11, "
              "linearised at rest)\n",
              format_human(r.dt_target).c_str(), format_human(r.safety).c_str(),
              format_human(r.dt_design).c_str());
  if (r.kind == MassScalingCase::no_mass_helps) {
    std::printf("answer       no mass helps: Rayleigh damping alpha = %s 1/s alone is unstable "
                "at dt_g (2 dt_g alpha >= 4); mass scaling needs dt* < 2 f / alpha = %s s\n",
                format_human(params.rayleigh_mass).c_str(), format_human(r.dt_no_mass).c_str());
    return status;
  }
  std::printf("  as given     exact dt limit %s s: %s at dt_g\n",
              limit(r.dt_limit_before).c_str(), scaled ? "unstable" : "stable");
  if (scaled) print_report(s);
  if (s.ran)
    std::printf("  run at dt* = %s s with the %s masses: %s%s\n", format_human(r.dt_target).c_str(),
                scaled ? "scaled" : "given", s.run.verified() ? "verified: " : "NOT verified: ",
                verdict_text(s.run.result, s.run.rules).c_str());
  if (!a.write_scene.empty()) std::printf("  wrote        %s\n", a.write_scene.c_str());
  if (!a.vtk.empty()) std::printf("  wrote        %s (point array added_mass)\n", a.vtk.c_str());
  if (!scaled) {
    std::printf("answer       nothing to add: stable at dt_g = %s s as given (exact dt limit %s s)\n",
                format_human(r.dt_design).c_str(), limit(r.dt_limit_before).c_str());
  } else if (r.over_cap) {
    std::printf("answer       over the cap: %s of the free mass > %s; the largest dt* within it "
                "is %s s (adds at most %s)\n",
                percent(r.added_fraction()).c_str(), percent(r.cap).c_str(),
                format_human(r.dt_cap).c_str(),
                percent(r.free_mass > 0 ? r.dt_cap_added / r.free_mass : 0).c_str());
  } else {
    std::printf("answer       add %s (%s of the free mass) to %d node%s: stable at dt* = %s s "
                "(exact limit %s s)%s\n",
                format_human(r.added).c_str(), percent(r.added_fraction()).c_str(),
                r.scaled_count, r.scaled_count == 1 ? "" : "s", format_human(r.dt_target).c_str(),
                limit(r.dt_limit).c_str(),
                run_ok ? "" : "; its run did not settle: do not use it as is");
  }
  return status;
}

MassScaleFlags add_mass_scale_flags(CLI::App* cmd, MassScaleArgs& mass, int& substeps,
                                    CLI::Option* dt_opt, CLI::Option* frame_dt_opt) {
  MassScaleFlags f;
  f.target = cmd->add_option("--mass-scale", mass.dt_target,
                                "target time step dt* (s): the least mass to add to the nodes "
                                "that limit the step so that dt* is stable (SPEC 11), checked "
                                "by a run. Exit 1 over the cap")
                    ->check(finite_positive());
  f.target->excludes(dt_opt)->excludes(frame_dt_opt);
  f.substeps = cmd->add_option("--substeps", substeps,
                                    "with --frame-dt: mass scaling for dt* = frame / substeps")
                        ->check(CLI::Range(1, 1000000))
                        ->needs(frame_dt_opt);
  f.only[0] = cmd->add_option("--safety", mass.safety,
                                    "with --mass-scale: design for dt* / safety (default 0.9)")
                        ->check(CLI::Range(0.0, 1.0))->check(finite_positive());
  f.only[1] =
      cmd->add_option("--max-added-mass", mass.max_added,
                      "with --mass-scale: the cap on the added mass, % of the free mass "
                      "(default 5)")
          ->check(finite_non_negative());
  f.only[2] = cmd->add_option("--write-scene", mass.write_scene,
                                    "with --mass-scale: write the scene with the scaled masses "
                                    "(TOML, at dt*; run, bounds and check read it)");
  f.only[3] = cmd->add_option("--vtk", mass.vtk,
                                    "with --mass-scale: write the scaled model at rest as one "
                                    ".vtu with the point array added_mass");
  f.only[4] = cmd->add_flag("--json", mass.json,
                                  "with --mass-scale: the answer as one JSON object");
  return f;
}

}  // namespace dampbound::app
