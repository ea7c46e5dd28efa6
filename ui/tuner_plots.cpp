#include "ui/tuner_plots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/io/report.hpp"
#include "ui/trace_plots.hpp"

namespace dampbound::ui {

std::string current_run_label(const Tuner& tuner) {
  return "current: " + verdict_short(tuner.session().result());
}

std::vector<PlotRefLine> verdict_markers(const RunResult& r) {
  const ImU32 green = IM_COL32(80, 200, 100, 255), amber = IM_COL32(235, 170, 40, 255),
              red = IM_COL32(225, 60, 60, 255);
  std::vector<PlotRefLine> out;
  const auto mark = [&](const char* what, int it, ImU32 color, bool dashed) {
    if (it > 0)
      out.push_back({std::string(what) + " " + std::to_string(it), LineAxis::x,
                     static_cast<double>(it), color, dashed});
  };
  mark("first entry", r.first_entry, green, true);
  mark("left at", r.left_at, amber, true);
  if (r.outcome == Outcome::settled) mark("settled at", r.settled_at, green, false);
  if (r.outcome == Outcome::diverged) mark("diverged at", r.iterations, red, false);
  return out;
}

PlotSpec tuner_displacement_plot(Tuner& tuner, const TunerPlotOptions& options) {
  const StopRules& rules = tuner.session().rules();
  const double threshold = rules.restore_fraction * rules.reference;
  std::vector<TraceView> current;
  if (options.show_current)
    current.push_back({current_run_label(tuner),
                       options.full_traces ? &tuner.session().trace() : &tuner.reduced_trace(),
                       tuner.current_color()});
  PlotSpec p = displacement_plot(current, options.log_y, threshold,
                                 options.show_max && options.show_current,
                                 "Displacement of node " + std::to_string(tuner.session().watched()));
  if (options.show_pins) {
    std::vector<TraceView> views;
    for (const Pin& pin : tuner.pins())
      if (pin.visible && pin.scene == tuner.scene().name)  // another scene's pin: its own nodes
        views.push_back({pin.name + " (" + verdict_short(pin.result) + ")",
                         options.full_traces ? &pin.trace : &pin.reduced, pin.color});
    PlotSpec pins = displacement_plot(views, options.log_y, 0, false);
    // Pins first, so the live run is drawn on top of them.
    pins.series.insert(pins.series.end(), std::make_move_iterator(p.series.begin()),
                       std::make_move_iterator(p.series.end()));
    p.series = std::move(pins.series);
  }
  show_coincident(p);
  for (PlotSeries& s : p.series) drop_flat_runs(s);
  if (options.show_current) {
    const std::vector<PlotRefLine> marks = verdict_markers(tuner.session().result());
    p.ref_lines.insert(p.ref_lines.end(), marks.begin(), marks.end());
  }
  return p;
}

void show_coincident(PlotSpec& spec) {
  std::vector<PlotSeries>& ss = spec.series;
  const std::vector<std::string> labels = [&] {
    std::vector<std::string> l;
    for (const PlotSeries& s : ss) l.push_back(s.label);
    return l;
  }();
  auto equal = [](double a, double b) {
    return a == b || std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b));
  };
  for (size_t j = ss.size(); j-- > 1;) {
    std::string same;
    for (size_t i = 0; i < j; ++i) {
      const PlotSeries &lo = ss[i], &hi = ss[j];
      const size_t n = std::min({lo.x.size(), lo.y.size(), hi.x.size(), hi.y.size()});
      size_t shared = 0, finite = 0;
      for (size_t k = 0; k < n; ++k) {
        if (!std::isfinite(lo.y[k]) || !std::isfinite(hi.y[k])) continue;
        ++finite;
        shared += lo.x[k] == hi.x[k] && equal(lo.y[k], hi.y[k]);
      }
      if (shared == 0 || 4 * shared < finite) continue;  // a few crossings are no overlap
      ss[i].thickness = std::max(ss[i].thickness, ss[j].thickness + 3.0f);
      // Equal wherever both have data (a pin may be shorter than the run it equals): named
      // in the legend by the earlier label's first words ("lower bound (eq. 5)" -> "lower
      // bound"), which keeps the legend narrow.
      if (shared == finite && !labels[i].empty())
        same += (same.empty() ? "" : ", ") + labels[i].substr(0, labels[i].find(" ("));
    }
    if (!same.empty() && !ss[j].label.empty()) ss[j].label += " (= " + same + ")";
  }
}

void simplify_band(PlotBand& band, size_t max_columns) {
  const size_t n = std::min({band.x.size(), band.y_lo.size(), band.y_hi.size()});
  if (n < 3 || max_columns < 2) return;
  PlotBand out;
  out.label = band.label;
  out.color = band.color;
  auto push = [&](double x, double lo, double hi) {
    out.x.push_back(x);
    out.y_lo.push_back(lo);
    out.y_hi.push_back(hi);
  };
  // Buckets of k samples, each drawn flat from its first sample to the next bucket's: over that
  // span the band is what is feasible throughout it (the largest lower and the smallest upper
  // edge of the samples at both ends and between). A step in the data stays where it is,
  // instead of reaching a bucket early, and the band never shows more than the data allows.
  const size_t k = (n + max_columns - 1) / max_columns;
  for (size_t i0 = 0; i0 < n - 1; i0 += k) {
    const size_t i1 = std::min(i0 + k, n - 1);
    double lo = band.y_lo[i0], hi = band.y_hi[i0];
    for (size_t i = i0 + 1; i <= i1; ++i) {
      lo = std::fmax(lo, band.y_lo[i]);
      hi = std::fmin(hi, band.y_hi[i]);
    }
    push(band.x[i0], lo, hi);
    push(band.x[i1], lo, hi);
  }
  // Runs of equal samples: keep their ends only.
  auto same = [&](size_t a, size_t b) {
    return out.y_lo[a] == out.y_lo[b] && out.y_hi[a] == out.y_hi[b];
  };
  PlotBand lean;
  lean.label = out.label;
  lean.color = out.color;
  const size_t m = out.x.size();
  for (size_t i = 0; i < m; ++i) {
    if (i > 0 && i + 1 < m && same(i - 1, i) && same(i, i + 1)) continue;
    lean.x.push_back(out.x[i]);
    lean.y_lo.push_back(out.y_lo[i]);
    lean.y_hi.push_back(out.y_hi[i]);
  }
  band = std::move(lean);
}

void drop_flat_runs(PlotSeries& s) {
  const size_t n = std::min(s.x.size(), s.y.size());
  if (n < 3) return;
  std::vector<double> x, y;
  x.reserve(n);
  y.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    // An interior point of a run of equal y adds nothing to the line.
    if (i > 0 && i + 1 < n && s.y[i - 1] == s.y[i] && s.y[i] == s.y[i + 1]) continue;
    x.push_back(s.x[i]);
    y.push_back(s.y[i]);
  }
  s.x = std::move(x);
  s.y = std::move(y);
}

void envelope_headroom(PlotSpec& spec, double cap, double fraction) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const PlotSeries& s : spec.series)
    for (double v : s.y)
      if (std::isfinite(v) && v > 0) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  for (const PlotRefLine& l : spec.ref_lines)
    if (l.axis == LineAxis::y && std::isfinite(l.at) && l.at > 0) {
      lo = std::min(lo, l.at);
      hi = std::max(hi, l.at);
    }
  if (!(hi > 0) || !std::isfinite(lo)) return;
  if (cap > 0) hi = std::min(hi, cap);
  if (!(hi > lo)) hi = lo * 10;
  const double l0 = std::log10(lo), l1 = std::log10(hi);
  const double pad = 0.05 * (l1 - l0);
  spec.y.min = std::pow(10.0, l0 - pad);
  spec.y.max = std::pow(10.0, l1 + (l1 - l0) * fraction / (1.0 - fraction));
}

PlotSpec tuner_envelope_plot(Tuner& tuner, const TunerPlotOptions& options) {
  const std::vector<StepSample>& current =
      options.full_traces ? tuner.session().trace() : tuner.reduced_trace();
  const int watched = tuner.session().watched();
  const std::vector<double>& scales = tuner.session().model().spec().gamma_scale;
  const double scale = watched >= 0 && watched < static_cast<int>(scales.size())
                           ? scales[static_cast<size_t>(watched)]
                           : 1.0;
  PlotSpec p = envelope_plot(current, tuner.exact_gamma_max(),
                             "Damping bounds of node " + std::to_string(watched), scale);
  p.x.min = 0;
  const Model& model = tuner.session().model();
  if (current.empty() && watched >= 0 && watched < model.spec().node_count()) {
    // Before the first step the node's lower bound and the user's gamma are known already:
    // draw them across the empty axis instead of a blank plot.
    const auto i = static_cast<size_t>(watched);
    for (PlotSeries& s : p.series) {
      const bool lower = s.label.rfind("lower bound", 0) == 0, user = s.label == "user gamma";
      if (!lower && !user) continue;
      const double v = lower ? model.lower_bound[i] : model.gamma[i];
      if (!(std::isfinite(v) && v > 0)) continue;
      s.x = {0.0, 1.0};
      s.y = {v, v};
    }
  }
  if (options.show_pins) {
    for (const Pin& pin : tuner.pins()) {
      if (!pin.visible || pin.scene != tuner.scene().name) continue;
      PlotSeries s;
      s.label = pin.name + " (effective)";
      s.color = pin.color;
      s.dashed = true;
      s.thickness = 1.5f;
      for (const StepSample& st : options.full_traces ? pin.trace : pin.reduced) {
        s.x.push_back(st.iteration);
        s.y.push_back(st.watched.gamma_eff);
      }
      p.series.push_back(std::move(s));
    }
  }
  // Live, the band is coarsened for the software rasteriser; an export draws every step (the
  // plot itself merges samples finer than a pixel column).
  if (!options.full_traces)
    for (PlotBand& b : p.bands) simplify_band(b, 240);
  show_coincident(p);
  for (PlotSeries& s : p.series) drop_flat_runs(s);
  // The upper bound (eq. 6) grows without limit as |v| -> 0: cap the axis at 100 x the
  // largest damping that matters, and keep the top part free for the legend.
  double ref = tuner.exact_gamma_max().value_or(0.0) * scale;
  for (const StepSample& st : current)
    for (double v : {st.watched.lower, st.watched.gamma, st.watched.gamma_eff})
      if (std::isfinite(v)) ref = std::max(ref, v);
  for (const PlotSeries& s : p.series)
    for (double v : s.y)
      if (current.empty() && std::isfinite(v)) ref = std::max(ref, v);
  envelope_headroom(p, ref > 0 ? 100 * ref : 0.0, 0.4);
  return p;
}

}  // namespace dampbound::ui
