#include "ui/trace_plots.hpp"

#include "core/io/format.hpp"
#include "core/io/report.hpp"

namespace dampbound::ui {

namespace {
std::vector<double> iterations(const std::vector<StepSample>& t) {
  std::vector<double> x;
  x.reserve(t.size());
  for (const StepSample& s : t) x.push_back(s.iteration);
  return x;
}

template <typename Field>
std::vector<double> column(const std::vector<StepSample>& t, Field f) {
  std::vector<double> y;
  y.reserve(t.size());
  for (const StepSample& s : t) y.push_back(f(s));
  return y;
}
}  // namespace

PlotSpec displacement_plot(const std::vector<TraceView>& views, bool log_y, double threshold,
                           bool show_max, const std::string& title) {
  PlotSpec p;
  p.title = title.empty() ? "Displacement of the watched node" : title;
  p.x.label = "iteration";
  p.x.min = 0;
  p.y.label = log_y ? "|x_c - X_c| (cm, log scale)" : "|x_c - X_c| (cm)";
  p.y.log = log_y;
  if (!log_y) p.y.min = 0;
  for (const TraceView& v : views) {
    if (!v.trace) continue;
    PlotSeries s;
    s.label = v.label;
    s.x = iterations(*v.trace);
    s.y = column(*v.trace, [](const StepSample& st) { return st.watched.displacement; });
    s.color = v.color;
    p.series.push_back(std::move(s));
    if (show_max) {
      PlotSeries m;
      m.label = v.label + " (max over nodes)";
      m.x = p.series.back().x;
      m.y = column(*v.trace, [](const StepSample& st) { return st.max_displacement; });
      m.color = with_alpha(v.color, 150);
      m.dashed = true;
      m.thickness = 1.5f;
      p.series.push_back(std::move(m));
    }
  }
  if (threshold > 0) {
    PlotRefLine h;
    h.label = "restore threshold " + format_number(threshold) + " cm";
    h.at = threshold;
    p.ref_lines.push_back(h);
  }
  return p;
}

PlotSpec envelope_plot(const std::vector<StepSample>& trace, std::optional<double> exact_gamma_max,
                       const std::string& title, double gamma_scale) {
  PlotSpec p;
  p.title = title.empty() ? "Damping bounds of the watched node" : title;
  p.x.label = "iteration";
  p.y.label = "damping gamma (mass unit/s, log scale)";
  p.y.log = true;
  const std::vector<double> x = iterations(trace);
  PlotBand band;
  band.label = "feasible band";
  band.x = x;
  band.y_lo = column(trace, [](const StepSample& s) { return s.watched.lower; });
  band.y_hi = column(trace, [](const StepSample& s) { return s.watched.upper; });
  band.color = IM_COL32(44, 160, 44, 60);
  auto series = [&](const char* label, std::vector<double> y, ImU32 color, bool dashed,
                    float thickness) {
    PlotSeries s;
    s.label = label;
    s.x = x;
    s.y = std::move(y);
    s.color = color;
    s.dashed = dashed;
    s.thickness = thickness;
    p.series.push_back(std::move(s));
  };
  series("lower bound (eq. 5)", band.y_lo, IM_COL32(31, 119, 180, 255), false, 2.0f);
  series("upper bound (eq. 6)", band.y_hi, IM_COL32(214, 39, 40, 255), false, 2.0f);
  // SPEC 9: below this the linearised step is guaranteed stable (<= 0 is not drawn on log y).
  series("safe bound", column(trace, [](const StepSample& s) { return s.watched.safe; }),
         IM_COL32(23, 190, 207, 255), false, 2.0f);
  series("user gamma", column(trace, [](const StepSample& s) { return s.watched.gamma; }),
         IM_COL32(127, 127, 127, 255), true, 1.5f);
  series("effective gamma", column(trace, [](const StepSample& s) { return s.watched.gamma_eff; }),
         IM_COL32(255, 127, 14, 255), false, 2.0f);
  p.bands.push_back(std::move(band));
  // The exact limit is of the user's gamma; the node is damped at gamma_i = gamma * scale.
  if (exact_gamma_max && *exact_gamma_max * gamma_scale > 0) {
    PlotRefLine h;
    h.label = "exact linear limit";
    if (gamma_scale != 1) h.label += " x gamma_scale " + format_digits(gamma_scale, 4);
    h.at = *exact_gamma_max * gamma_scale;
    h.color = IM_COL32(148, 103, 189, 255);
    p.ref_lines.push_back(h);
  }
  return p;
}

PlotSpec figure_plot(const FigureData& figure) {
  std::vector<TraceView> views;
  int k = 0;
  for (const FigureRun& run : figure.runs) {
    views.push_back(
        {run.label + " (" + verdict_short(run.result) + ")", &run.trace, palette_color(k++)});
  }
  PlotSpec p = displacement_plot(views, figure.log_y, figure.restore_threshold, false,
                                 figure.title);
  p.y.label = figure.log_y ? "|x_c - X_c| of the perturbed node (cm, log10 scale)"
                           : "|x_c - X_c| of the perturbed node (cm)";
  return p;
}

}  // namespace dampbound::ui
