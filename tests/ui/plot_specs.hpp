#pragma once
// Synthetic plots shared by the render tests (tests/ui/egl_render_test.cpp) and the render
// benchmark (bench/plot_render_bench.cpp): one drawing checked pixel by pixel, and timed.
#include <imgui.h>

#include <cmath>
#include <limits>

#include "ui/plot_spec.hpp"

namespace dampbound::ui {

inline constexpr ImU32 kRed = IM_COL32(220, 20, 30, 255);

/// A red line y = x over [0, 10] and a grey threshold at y = 8.
inline PlotSpec line_spec() {
  PlotSpec spec;
  spec.title = "y = x";
  spec.x.label = "x (cm)";
  spec.y.label = "y (cm)";
  PlotSeries s;
  s.label = "y = x";
  s.color = kRed;
  s.thickness = 3.0f;
  for (int i = 0; i <= 100; ++i) {
    s.x.push_back(i * 0.1);
    s.y.push_back(i * 0.1);
  }
  spec.series.push_back(s);
  PlotRefLine h;
  h.label = "threshold";
  h.at = 8.0;
  h.color = IM_COL32(90, 90, 90, 255);
  spec.ref_lines.push_back(h);
  return spec;
}

/// The upper bound of band_spec() at sample i: decaying and oscillating, +inf every 1000th
/// sample (a break in the line, the band to the top of the plot).
inline double band_upper(int i) {
  const double t = i;
  if (i % 1000 == 0) return std::numeric_limits<double>::infinity();
  return 1e-3 + 0.05 * std::exp(-t / 3000.0) * (1.0 + 0.9 * std::sin(t * 0.05));
}

/// A damping-bounds plot on a log axis: the feasible band between a lower bound at 2e-3 and
/// band_upper(), both bounds as 10000-point lines, and the user's gamma at 4e-3.
inline PlotSpec band_spec() {
  PlotSpec spec;
  spec.title = "Damping bounds of the watched node";
  spec.x.label = "iteration";
  spec.y.label = "damping γ";
  spec.y.log = true;
  PlotBand band;
  band.label = "feasible damping";
  PlotSeries lo, hi;
  lo.label = "lower bound 2√(mκ) (eq. 5)";
  lo.color = palette_color(0);
  hi.label = "upper bound (eq. 6)";
  hi.color = palette_color(3);
  const int n = 10000;
  for (int i = 0; i < n; ++i) {
    band.x.push_back(i);
    band.y_lo.push_back(2e-3);
    band.y_hi.push_back(band_upper(i));
  }
  lo.x = hi.x = band.x;
  lo.y = band.y_lo;
  hi.y = band.y_hi;
  spec.bands.push_back(band);
  spec.series = {lo, hi};
  PlotRefLine user;
  user.label = "user γ";
  user.at = 4e-3;
  spec.ref_lines.push_back(user);
  return spec;
}

}  // namespace dampbound::ui
