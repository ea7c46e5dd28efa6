#include "ui/tuner_save.hpp"

#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "core/analysis/expect.hpp"
#include "core/io/files.hpp"
#include "core/io/report.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound::ui {

namespace {

/// The run's result at its verdict, from its trace: accumulate() over the steps up to the
/// verdict, as run_protocol does (the session may have stepped on past the verdict, and its
/// final displacement and counts with it).
RunResult result_at_verdict(const std::vector<StepSample>& trace, const StopRules& rules) {
  RunResult r;
  for (const StepSample& st : trace) {
    accumulate(r, st, rules);
    if (r.outcome != Outcome::running) break;
  }
  return r;
}

/// The result a check of `label` will see: the run's own, taken at its verdict, when it can
/// be replayed as it went; else a headless replay.
RunResult checked_result(const SceneSpec& scene, const std::string& label,
                         const std::vector<StepSample>& trace, const StopRules& rules,
                         bool replayable, const RunResult& own, const std::string& who,
                         std::vector<std::string>* notes) {
  if (replayable) {
    const RunResult seen = result_at_verdict(trace, rules);
    if (seen.outcome != Outcome::running) return seen;
    // SPEC 8's proof ended the run before its limit: the verdict is its own, and `check`
    // steps a run whose expectations assert its end to the limit (docs/settled.md), so the
    // end is taken there.
    if (own.outcome == Outcome::settled && own.iterations < rules.max_iterations)
      return run_labelled(scene, label, rules.rule, true);
  }
  const RunResult r = run_labelled(scene, label, rules.rule, true);
  if (notes != nullptr)
    notes->push_back(who + (replayable ? " had no verdict yet" : " was changed by hand") +
                     ": saved with its headless replay, " + verdict_short(r));
  return r;
}

}  // namespace

SceneSpec tuner_saved_scene(const Tuner& tuner, const ExpectTolerance& tolerance,
                            std::vector<std::string>* notes) {
  SceneSpec s = tuner.scene();
  s.params = tuner.params();
  s.rules = tuner.session().rules();
  s.runs.clear();
  s.expectations.clear();
  std::set<std::string> labels;
  std::vector<const Pin*> pins;
  for (const Pin& p : tuner.pins()) {
    if (p.scene != s.name) {
      if (notes != nullptr) notes->push_back("pin '" + p.name + "' is of another scene: left out");
      continue;
    }
    std::string label = p.name.empty() ? params_label(p.params) : p.name;
    for (int k = 2; !labels.insert(label).second; ++k) label = p.name + " (" + std::to_string(k) + ")";
    StopRules rules = s.rules;
    rules.max_iterations = p.rules.max_iterations;
    s.runs.push_back({label, p.params, rules});
    pins.push_back(&p);
  }
  s.expectations.push_back(expectation_for(
      checked_result(s, "", tuner.session().trace(), s.rules, tuner.replayable(),
                     tuner.session().result(), "the current run", notes),
      "", tolerance, s.rules.rule));
  for (size_t k = 0; k < pins.size(); ++k) {
    const std::string& label = s.runs[k].label;
    s.expectations.push_back(expectation_for(
        checked_result(s, label, pins[k]->trace, s.runs[k].rules, pins[k]->replayable,
                       pins[k]->result, "pin '" + label + "'", notes),
        label, tolerance, s.rules.rule));
  }
  return s;
}

std::string save_tuner_scene(const Tuner& tuner, const std::string& path,
                             const ExpectTolerance& tolerance, std::vector<std::string>* notes) {
  if (path.empty()) throw InputError("save as scene: no file name given");
  const SceneSpec s = tuner_saved_scene(tuner, tolerance, notes);
  const std::vector<std::string> header = {
      "Saved by the dampbound tuner from " + (s.path.empty() ? s.name : s.path) + ".",
      "Check it headless with: dampbound check " + path,
      "Each [[run]] is a pinned run; each [[expect]] is what it measured, within the",
      "tolerances chosen when saving (edit them here as you like)."};
  write_file_atomic(path, [&](std::ostream& out) { write_scene_toml(out, s, path, header); });
  return "saved " + path + ": " + std::to_string(s.runs.size()) + " runs, " +
         std::to_string(s.expectations.size()) + " expectations (dampbound check " + path + ")";
}

PinRequest parse_pin_request(const std::string& text, const Params& base, int max_iterations,
                             const std::string& flag) {
  PinRequest r{"", base, max_iterations};
  auto bad = [&](const std::string& why) {
    throw InputError(flag + " " + text + ": " + why);
  };
  auto number = [&](const std::string& key, const std::string& v, bool positive) {
    char* end = nullptr;
    const double x = std::strtod(v.c_str(), &end);
    if (v.empty() || end != v.c_str() + v.size() || !std::isfinite(x) || x < 0 ||
        (positive && x == 0))
      bad(key + " must be a finite number " + (positive ? "> 0" : ">= 0") + " (got '" + v + "')");
    return x;
  };
  std::stringstream items(text);
  std::string item;
  bool any = false;
  while (std::getline(items, item, ',')) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos) bad("expected KEY=VALUE, got '" + item + "'");
    const std::string key = item.substr(0, eq), v = item.substr(eq + 1);
    any = true;
    if (key == "m") r.params.m = number(key, v, true);
    else if (key == "kappa") r.params.kappa = number(key, v, true);
    else if (key == "gamma") r.params.gamma = number(key, v, false);
    else if (key == "dt") r.params.dt = number(key, v, true);
    else if (key == "factor") r.params.factor = number(key, v, false);
    else if (key == "name") r.name = v;
    else if (key == "max_iterations") {
      const double n = number(key, v, true);
      if (n != std::floor(n) || n > 100000000) bad("max_iterations must be an integer in 1..1e8");
      r.max_iterations = static_cast<int>(n);
    } else if (key == "policy") {
      const auto p = parse_policy(v);
      if (!p) bad("policy must be fixed, clamp, upper or lower");
      r.params.policy = *p;
    } else if (key == "integrator") {
      const auto i = parse_integrator(v);
      if (!i) bad("unknown integrator '" + v + "'");
      r.params.integrator = *i;
    } else {
      bad("unknown key '" + key +
          "' (m, kappa, gamma, dt, policy, factor, integrator, max_iterations, name)");
    }
  }
  if (!any) bad("expected KEY=VALUE");
  if (const auto why = validate(r.params)) bad(*why);
  return r;
}

Pin& pin_run(Tuner& tuner, const PinRequest& request) {
  const Params base = tuner.params();
  const int base_limit = tuner.session().rules().max_iterations;
  tuner.set_params(request.params);
  tuner.set_max_iterations(request.max_iterations);
  tuner.reset();
  while (tuner.session().result().outcome == Outcome::running && tuner.can_step())
    if (tuner.step(1) == 0) break;  // one at a time: the run stops at its verdict
  Pin& pin = tuner.pin(request.name);
  tuner.set_params(base);
  tuner.set_max_iterations(base_limit);
  tuner.reset();
  return pin;
}

}  // namespace dampbound::ui
