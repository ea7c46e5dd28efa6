#include "core/analysis/expect.hpp"

#include <cmath>
#include <map>
#include <utility>

#include "core/analysis/limits_diff.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/mass_scaling_scene.hpp"
#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound {

RunResult run_labelled(const SceneSpec& scene, const std::string& label, StopRule rule,
                       bool to_the_limit) {
  Params params = scene.params;
  StopRules rules = scene.rules;
  for (const RunSpec& r : scene.runs)
    if (r.label == label) params = r.params, rules = r.rules;
  rules.rule = rule;
  Session session(scene, params, rules);
  if (to_the_limit) session.set_early_stop(false);
  return session.run_to_end();
}

namespace {

/// SPEC 11 for the run labelled `label` at dt*, its check run included.
SceneMassScaling mass_scaling_of(const SceneSpec& scene, const std::string& label, double dt) {
  Params params = scene.params;
  StopRules rules = scene.rules;
  for (const RunSpec& r : scene.runs)
    if (r.label == label) params = r.params, rules = r.rules;
  return scene_mass_scaling(scene, params, rules, dt);
}

/// Whether `e` asserts what a run's last iteration has: its displacement, counts or iteration
/// (SPEC 8's early stop would end a settled run sooner, docs/settled.md).
bool asserts_the_end(const Expectation& e) {
  return e.iterations_min || e.iterations_max || e.max_displacement_below ||
         e.unstabilisable_max || e.violations_max || e.violations_min;
}

bool asserts_a_run(const Expectation& e) {
  return e.outcome || e.iterations_min || e.first_entry_min || e.left || e.left_at_min ||
         e.settled_at_min || e.max_displacement_below || e.unstabilisable_max ||
         e.violations_max || e.violations_min;
}

/// dt_limit_min and substeps_max: the exact limits at rest at the run's parameters (no run).
void judge_limits(const SceneSpec& scene, const Expectation& e,
                  std::vector<ExpectationResult>& out) {
  Params params = scene.params;
  for (const RunSpec& r : scene.runs)
    if (r.label == e.run) params = r.params;
  params.policy = DampingPolicy::fixed;
  ExactOptions options;
  options.max_factor_flops = kDefaultFactorBudget;
  options.with_radius = false;
  const Model model = compile_model(scene.model, params);
  const ExactStability x = exact_stability(model, model.spec().rest, params, options);
  const double dt_limit = x.computed() ? x.dt_max : std::nan("");
  const std::string limit = x.computed() ? format_number(dt_limit) + " s"
                                         : "not computed (" + x.over_budget_reason() + ")";
  if (e.dt_limit_min)
    out.push_back({scene.path, e.line, e.run,
                   "[exact] dt_limit >= " + format_number(*e.dt_limit_min) + " s", limit,
                   dt_limit >= *e.dt_limit_min});
  if (e.substeps_max) {
    const double frame = e.frame_dt ? *e.frame_dt : params.dt;
    const int n = limit_substeps(frame, dt_limit);
    out.push_back({scene.path, e.line, e.run,
                   "[exact] substeps of " + format_number(frame) + " s <= " +
                       std::to_string(*e.substeps_max),
                   n > 0 ? std::to_string(n) + " (dt limit " + limit + ")" : "none (dt limit " + limit + ")",
                   n > 0 && n <= *e.substeps_max});
  }
}

}  // namespace

std::vector<ExpectationResult> check_expectations(const SceneSpec& scene) {
  std::map<std::pair<std::string, StopRule>, RunResult> results;
  std::map<std::pair<std::string, double>, SceneMassScaling> scalings;
  std::vector<ExpectationResult> out;
  std::map<std::pair<std::string, StopRule>, bool> to_the_limit;
  for (const Expectation& e : scene.expectations)
    to_the_limit[std::make_pair(e.run, e.rule)] |= asserts_the_end(e);
  for (const Expectation& e : scene.expectations) {
    if (e.dt_limit_min || e.substeps_max) judge_limits(scene, e, out);
    if (!asserts_a_run(e) && !e.mass_scale_dt) continue;
    const SceneMassScaling* scaling = nullptr;
    const RunResult* run = nullptr;
    if (e.mass_scale_dt) {
      const auto key = std::make_pair(e.run, *e.mass_scale_dt);
      auto it = scalings.find(key);
      if (it == scalings.end())
        it = scalings.emplace(key, mass_scaling_of(scene, e.run, *e.mass_scale_dt)).first;
      scaling = &it->second;
      run = &scaling->run.result;  // a default result (never run) where no mass helps
    } else {
      const auto key = std::make_pair(e.run, e.rule);
      auto it = results.find(key);
      if (it == results.end())
        it = results.emplace(key, run_labelled(scene, e.run, e.rule, to_the_limit[key])).first;
      run = &it->second;
    }
    const RunResult& r = *run;
    const std::string rule = std::string("[") + to_string(e.rule) + "] " +
                             (e.mass_scale_dt ? "[mass scaled for dt* = " +
                                                    format_number(*e.mass_scale_dt) + " s] "
                                              : std::string());
    auto add = [&](const std::string& what, const std::string& measured, bool pass) {
      out.push_back({scene.path, e.line, e.run, rule + what, measured, pass});
    };
    // An iteration range; 0 (none) is outside every range.
    auto range = [&](const char* name, int value, int lo, int hi) {
      add(std::string(name) + " in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]",
          value > 0 ? std::to_string(value) : std::string("none"), value >= lo && value <= hi);
    };
    const bool run_asked = e.outcome || e.iterations_min || e.first_entry_min || e.left ||
                           e.left_at_min || e.settled_at_min || e.max_displacement_below ||
                           e.unstabilisable_max || e.violations_max || e.violations_min;
    if (scaling && !scaling->ran && run_asked) {  // no mass helps, or over the cap: no run
      add("the run at dt* with the scaled masses", std::string("not run (") +
                                                      to_string(scaling->result.kind) +
                                                      (scaling->result.over_cap ? ", over the cap)" : ")"),
          false);
      run = nullptr;
    }
    if (run) {  // the fields judged on the run
      if (e.outcome) {
        StopRules rules = scene.rules;
        for (const RunSpec& rs : scene.runs)
          if (rs.label == e.run) rules = rs.rules;
        rules.rule = e.rule;
        if (scaling) rules = scaling->run.rules;  // its iteration limit covers the scene's time
        add(std::string("outcome == ") + to_string(*e.outcome), verdict_text(r, rules),
            r.outcome == *e.outcome);
      }
      if (e.iterations_min) range("iterations", r.iterations, *e.iterations_min, *e.iterations_max);
      if (e.first_entry_min)
        range("first_entry", r.first_entry, *e.first_entry_min, *e.first_entry_max);
      if (e.left)
        add(std::string("left == ") + (*e.left ? "true" : "false"),
            r.left_at > 0 ? "left at " + std::to_string(r.left_at) : "never left",
            (r.left_at > 0) == *e.left);
      if (e.left_at_min) range("left_at", r.left_at, *e.left_at_min, *e.left_at_max);
      if (e.settled_at_min) range("settled_at", r.settled_at, *e.settled_at_min, *e.settled_at_max);
      if (e.max_displacement_below)
        add("max displacement < " + format_number(*e.max_displacement_below) + " cm",
            format_number(r.max_displacement), r.max_displacement < *e.max_displacement_below);
      if (e.unstabilisable_max)
        add("unstabilisable node-steps <= " + std::to_string(*e.unstabilisable_max),
            std::to_string(r.unstabilisable), r.unstabilisable <= *e.unstabilisable_max);
      if (e.violations_max)
        add("violating node-steps <= " + std::to_string(*e.violations_max),
            std::to_string(r.violations), r.violations <= *e.violations_max);
      if (e.violations_min)
        add("violating node-steps >= " + std::to_string(*e.violations_min),
            std::to_string(r.violations), r.violations >= *e.violations_min);
    }
    if (scaling) {
      const MassScalingResult& m = scaling->result;
      const double percent = 100 * m.added_fraction();
      if (e.added_mass_min)
        add("added mass in [" + format_number(*e.added_mass_min) + ", " +
                format_number(*e.added_mass_max) + "] % of the free mass",
            format_number(percent) + " % (" + to_string(m.kind) + ")",
            percent >= *e.added_mass_min && percent <= *e.added_mass_max);
      if (e.scaled_nodes_min)
        add("scaled nodes in [" + std::to_string(*e.scaled_nodes_min) + ", " +
                std::to_string(*e.scaled_nodes_max) + "]",
            std::to_string(m.scaled_count), m.scaled_count >= *e.scaled_nodes_min &&
                                                m.scaled_count <= *e.scaled_nodes_max);
    }
  }
  return out;
}

}  // namespace dampbound
