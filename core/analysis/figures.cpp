#include "core/analysis/figures.hpp"

#include <ostream>

#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound {

namespace {
FigureRun make_run(const std::string& label, const Params& p, const StopRules& r) {
  FigureRun run;
  run.label = label;
  run.params = p;
  run.rules = r;
  return run;
}
}  // namespace

void run_figure(const SceneSpec& scene, FigureData& figure) {
  for (FigureRun& run : figure.runs) {
    Session session(scene, run.params, run.rules);
    run.result = session.run_to_end();
    run.trace = session.trace();
  }
  figure.watched = scene.watched;
  if (!figure.runs.empty())
    figure.restore_threshold =
        figure.runs.front().rules.restore_fraction * figure.runs.front().rules.reference;
}

FigureData figure_fig1(const SceneSpec& plane) {
  FigureData f;
  f.name = "fig1";
  f.title = "Fig. 1: kappa = m = 0.001, dt = 0.05 s, fixed gamma (lower bound 0.002)";
  Params p = plane.params;
  p.m = 0.001, p.kappa = 0.001, p.dt = 0.05, p.policy = DampingPolicy::fixed;
  StopRules r = plane.rules;
  r.rule = StopRule::first_entry;  // SPEC 8: what reproduces the paper stops as it did
  r.max_iterations = 1000;
  for (double gamma : {0.0005, 0.001, 0.002}) {
    p.gamma = gamma;
    f.runs.push_back(make_run("gamma = " + format_number(gamma), p, r));
  }
  run_figure(plane, f);
  return f;
}

FigureData figure_fig2(const SceneSpec& plane) {
  FigureData f;
  f.name = "fig2";
  f.title = "Fig. 2: kappa = 0.1, m = 0.005, dt = 0.05 s, gamma = factor x upper bound (eq. 6)";
  f.log_y = true;
  Params p = plane.params;
  p.m = 0.005, p.kappa = 0.1, p.dt = 0.05, p.policy = DampingPolicy::upper;
  StopRules r = plane.rules;
  r.rule = StopRule::first_entry;
  r.max_iterations = 10000;
  for (double factor : {1.0, 1.05}) {
    p.factor = factor;
    f.runs.push_back(make_run("gamma = " + format_number(factor) + " x upper", p, r));
  }
  run_figure(plane, f);
  return f;
}

FigureData figure_scene(const SceneSpec& scene) {
  FigureData f;
  f.name = scene.name.empty() ? "scene" : scene.name;
  f.title = scene.description.empty() ? f.name : scene.description;
  // A scene's figure is no reproduction of the paper: its runs are judged by the settled rule
  // (SPEC 8) and drawn to their limit or divergence.
  auto settled = [](StopRules rules) {
    rules.rule = StopRule::settled;
    return rules;
  };
  if (scene.runs.empty()) f.runs.push_back(make_run(f.name, scene.params, settled(scene.rules)));
  for (const RunSpec& r : scene.runs)
    f.runs.push_back(make_run(r.label, r.params, settled(r.rules)));
  run_figure(scene, f);
  // A diverging run's displacement dwarfs the others' on a linear axis: use log10 then.
  for (const FigureRun& r : f.runs) f.log_y = f.log_y || r.result.outcome == Outcome::diverged;
  return f;
}

void write_figure_csv(std::ostream& out, const FigureData& figure) {
  bool header = true;
  for (const FigureRun& run : figure.runs) {
    write_trace_csv(out, run.trace, run.label, header);
    header = false;
  }
}

}  // namespace dampbound
