#include "core/expect.hpp"

#include <map>

#include "core/io.hpp"
#include "core/session.hpp"

namespace dampbound {

RunResult run_labelled(const SceneSpec& scene, const std::string& label) {
  Params params = scene.params;
  StopRules rules = scene.rules;
  for (const RunSpec& r : scene.runs)
    if (r.label == label) params = r.params, rules = r.rules;
  Session session(scene, params, rules);
  return session.run_to_end();
}

std::vector<ExpectationResult> check_expectations(const SceneSpec& scene) {
  std::map<std::string, RunResult> results;
  std::vector<ExpectationResult> out;
  for (const Expectation& e : scene.expectations) {
    auto it = results.find(e.run);
    if (it == results.end()) it = results.emplace(e.run, run_labelled(scene, e.run)).first;
    const RunResult& r = it->second;
    auto add = [&](const std::string& what, const std::string& measured, bool pass) {
      out.push_back({scene.path, e.line, e.run, what, measured, pass});
    };
    if (e.outcome)
      add(std::string("outcome == ") + to_string(*e.outcome),
          std::string(to_string(r.outcome)) + " at " + std::to_string(r.iterations),
          r.outcome == *e.outcome);
    if (e.iterations_min)
      add("iterations in [" + std::to_string(*e.iterations_min) + ", " +
              std::to_string(*e.iterations_max) + "]",
          std::to_string(r.iterations),
          r.iterations >= *e.iterations_min && r.iterations <= *e.iterations_max);
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
  return out;
}

}  // namespace dampbound
