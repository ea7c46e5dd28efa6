#pragma once
// Plots of traces, shared by the live GUI and the headless figures: the displacement of the
// watched node (and the maximum over all nodes) and the bound envelope of eqs. 5-6.
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/figures.hpp"
#include "dampbound/physics/step.hpp"
#include "ui/plot_spec.hpp"

namespace dampbound::ui {

/// One trace to draw, with its legend label and colour.
struct TraceView {
  std::string label;
  const std::vector<StepSample>* trace = nullptr;
  ImU32 color = 0;
};

/// Displacement |x_c - X_c| (cm) of the watched node against iteration for every view, the
/// maximum over all nodes (dashed, when show_max), and the restore threshold line.
PlotSpec displacement_plot(const std::vector<TraceView>& views, bool log_y, double threshold,
                           bool show_max, const std::string& title = "");

/// The bound envelope of the watched node against iteration on a log axis: the lower bound
/// (eq. 5), the upper bound (eq. 6), the user's gamma and the effective gamma, with the
/// feasible band [lower, upper] shaded; `exact_gamma_max`, when given, as a line (SPEC 7).
/// Every curve is the node's own gamma_i; the exact limit, of the user's gamma, is drawn
/// times the node's `gamma_scale` (gamma_i = gamma * gamma_scale_i) and labelled so.
PlotSpec envelope_plot(const std::vector<StepSample>& trace,
                       std::optional<double> exact_gamma_max = std::nullopt,
                       const std::string& title = "", double gamma_scale = 1);

/// A paper figure: the displacement of every run (the paper's Fig. 1 and Fig. 2 show only the
/// perturbed node), log axis when the figure asks for it.
PlotSpec figure_plot(const FigureData& figure);

}  // namespace dampbound::ui
