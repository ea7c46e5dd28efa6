// suggest --rayleigh --plot FILE.png: zeta(f) of the designed pair over the model's spectrum,
// rendered headless through EGL with the GUI's plot widget (the path `figure` takes).
#include "app/suggest_knobs.hpp"
#include "core/io/format.hpp"
#include "ui/render_png.hpp"

namespace dampbound::app::cmd_ui_rayleigh_plot {
namespace {

std::string plot(const RayleighDesign& d, const std::string& path) {
  ui::PlotSpec p;
  p.title = "Rayleigh damping ratio over the spectrum (alpha " + format_digits(d.alpha, 4) +
            " 1/s, beta " + format_digits(d.beta, 4) + " s)";
  p.x.label = "frequency f (Hz, log scale)";
  p.x.log = true;
  p.y.label = "damping ratio zeta(f) = alpha/(4 pi f) + beta pi f (log scale)";
  p.y.log = true;
  ui::PlotSeries s;
  s.label = d.stable ? "zeta(f), stable at the scene's dt" : "zeta(f), NOT stable at the scene's dt";
  s.x = d.curve_f;
  s.y = d.curve_zeta;
  s.color = ui::palette_color(0);
  p.series.push_back(s);
  if (!d.stable && d.feasible) {
    ui::PlotSeries m;
    m.label = "largest stable beta " + format_digits(d.beta_max, 4) + " s";
    m.x = d.curve_f;
    for (double f : d.curve_f) m.y.push_back(rayleigh_zeta(d.alpha, d.beta_max, f));
    m.color = ui::palette_color(3);
    m.dashed = true;
    p.series.push_back(m);
  }
  const auto vline = [&](const std::string& label, double at, ImU32 color, bool dashed) {
    ui::PlotRefLine l;
    l.label = label;
    l.axis = ui::LineAxis::x;
    l.at = at;
    l.color = color;
    l.dashed = dashed;
    p.ref_lines.push_back(l);
  };
  vline("lowest mode " + format_digits(d.f_lowest, 3) + " Hz", d.f_lowest, IM_COL32(127, 127, 127, 255), false);
  vline("highest mode " + format_digits(d.f_highest, 3) + " Hz", d.f_highest, IM_COL32(127, 127, 127, 255), false);
  vline("asked: zeta " + format_digits(d.zeta1, 3) + " at " + format_digits(d.f1, 3) + " Hz", d.f1,
        ui::palette_color(2), true);
  vline("asked: zeta " + format_digits(d.zeta2, 3) + " at " + format_digits(d.f2, 3) + " Hz", d.f2,
        ui::palette_color(4), true);
  return ui::render_plots_png({p}, 1, 1200, 700, path);
}

const bool registered = [] {
  rayleigh_plotter() = &plot;
  return true;
}();

}  // namespace
}  // namespace dampbound::app::cmd_ui_rayleigh_plot
