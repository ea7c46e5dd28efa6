#pragma once
// The paper's figures as data (no GL): which runs, their traces and results. The UI turns a
// FigureData into plots (ui/trace_plots.hpp); `figure` and `reproduce` render it headless.
#include <iosfwd>
#include <string>
#include <vector>

#include "dampbound/run/protocol.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// One run of a figure: its label, parameters, trace and result.
struct FigureRun {
  std::string label;
  Params params;
  StopRules rules;
  RunResult result;
  std::vector<StepSample> trace;
};

struct FigureData {
  std::string name;   ///< "fig1", "fig2" or the scene's name
  std::string title;
  bool log_y = false;  ///< displacement on a log10 axis (the paper's Fig. 2)
  double restore_threshold = 0;  ///< cm: restore_fraction * reference
  int watched = 0;
  std::vector<FigureRun> runs;
};

/// Paper Fig. 1 (SPEC 5) on the paper-plane scene: kappa = m = 0.001, dt = 0.05, policy fixed,
/// gamma 0.0005, 0.001, 0.002, 1000 iterations.
FigureData figure_fig1(const SceneSpec& paper_plane);

/// Paper Fig. 2: kappa = 0.1, m = 0.005, policy upper with factor 1.0 and 1.05, 10000
/// iterations, log10 displacement.
FigureData figure_fig2(const SceneSpec& paper_plane);

/// A scene's declared [[run]]s, or its own parameters when it declares none, each judged by the
/// settled rule (SPEC 8; fig1 and fig2 keep the paper's first entry); on a log10 axis when one
/// of them diverges.
FigureData figure_scene(const SceneSpec& scene);

/// Runs each FigureRun's parameters on the scene (through Session, the one step()).
void run_figure(const SceneSpec& scene, FigureData& figure);

/// Long CSV of every run: run label, then the trace columns of write_trace_csv.
void write_figure_csv(std::ostream& out, const FigureData& figure);

}  // namespace dampbound
