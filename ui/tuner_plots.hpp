#pragma once
// The tuner's two live plots as PlotSpecs (no GL): the bound envelope of the watched node and
// the displacement, with the pinned runs overlaid. Built from ui/trace_plots.hpp, the same
// functions the headless figures use, on decimated traces.
#include <string>

#include "ui/plot_spec.hpp"
#include "ui/tuner.hpp"

namespace dampbound::ui {

/// What the plots show.
struct TunerPlotOptions {
  bool log_y = false;     ///< displacement on a log10 axis
  bool show_max = true;   ///< the max displacement over all nodes (current run)
  bool show_pins = true;  ///< overlay the visible pins
  bool show_current = true;  ///< the current run (its curves, verdict markers, max over nodes)
  bool full_traces = false;  ///< every step (exports, as `figure` draws), not the reduced traces
};

/// Legend label of the current run: "current: <outcome>".
std::string current_run_label(const Tuner& tuner);

/// Vertical markers of a run's band history (SPEC 8): "first entry K" (green, dashed),
/// "left at L" (amber, dashed), "settled at S" (green, solid), "diverged at D" (red, solid);
/// only those that happened.
std::vector<PlotRefLine> verdict_markers(const RunResult& result);

/// Displacement of the watched node (and the max over nodes) against iteration for the
/// current run and the visible pins, with the 1 % restore threshold line and the current
/// run's verdict_markers().
PlotSpec tuner_displacement_plot(Tuner& tuner, const TunerPlotOptions& options);

/// Coarsens a band for drawing: at most about max_columns buckets of consecutive samples, each
/// flat over its span (the largest lower and the smallest upper edge of the span: where all of
/// it is feasible), then runs of equal samples reduced to their ends. A software rasteriser (llvmpipe) fills a
/// few wide quads far faster than hundreds of one-pixel slivers.
void simplify_band(PlotBand& band, size_t max_columns);

/// Removes the interior points of runs of equal y (a constant bound or gamma becomes one
/// segment): the same line with far fewer triangles to rasterise.
void drop_flat_runs(PlotSeries& series);

/// Keeps coincident lines visible: a series drawn under a later one that shares at least a
/// quarter of its samples with it (same x, same y) is widened to the later one's width + 3 px,
/// so it shows as an outline around it; a later series equal to an earlier one wherever both
/// have samples has " (= <earlier label up to its first ' ('>)" added to its label. Call
/// before drop_flat_runs (it compares sample by sample).
void show_coincident(PlotSpec& spec);

/// Sets a log y axis to the positive finite data of the series and lines, capped at `cap`
/// (when > 0), with the top `fraction` of the axis left free (for the legend).
void envelope_headroom(PlotSpec& spec, double cap, double fraction);

/// The bound envelope of the watched node (envelope_plot: lower, upper, user and effective
/// gamma, feasible band, log axis) with the exact linear limit when known, plus each visible
/// pin's effective gamma dashed in its colour, labelled "<pin> (effective)".
PlotSpec tuner_envelope_plot(Tuner& tuner, const TunerPlotOptions& options);

}  // namespace dampbound::ui
