#pragma once
// The pure maths of a plot axis: data ranges, tick values and labels, the data <-> pixel map.
// No GL context, no ImGui context: unit-tested in plot_test.cpp. Clipping and decimation of
// what is drawn are in plot_geometry.hpp.
#include "ui/plot_spec.hpp"

#include <string>
#include <vector>

namespace dampbound::ui {

/// A closed data interval [lo, hi], lo < hi after auto_range().
struct Range {
  double lo = 0.0;
  double hi = 1.0;
};

/// Pixel rectangle, min corner inclusive (screen coordinates: y grows downwards).
struct PixelRect {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  bool contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

/// True when v can be placed on the axis: finite, and > 0 on a log axis.
bool axis_valid(double v, bool log);

/// Grows a range from data values, ignoring those !axis_valid().
class RangeAccumulator {
 public:
  explicit RangeAccumulator(bool log) : log_(log) {}
  void add(double v);
  void add(const std::vector<double>& values);
  bool empty() const { return n_ == 0; }
  double lo() const { return lo_; }
  double hi() const { return hi_; }

 private:
  bool log_;
  int n_ = 0;
  double lo_ = 0.0, hi_ = 0.0;
};

/// Final axis range from accumulated data: pads by `pad` of the span (of the decades on a
/// log axis), widens a degenerate range, falls back to [0,1] (log: [1,10]) without data, then
/// applies the fixed ends of `axis`. Always returns lo < hi (lo > 0 on a log axis).
Range finish_range(const RangeAccumulator& acc, const AxisSpec& axis, double pad);

/// Auto range of one set of values (convenience over RangeAccumulator + finish_range).
Range auto_range(const std::vector<double>& values, const AxisSpec& axis, double pad = 0.05);

/// x range of everything in the spec (series, bands, vertical lines, heatmap edges).
Range plot_x_range(const PlotSpec& spec);

/// y range of everything in the spec; series and band samples whose x is outside `xr` are
/// ignored, so a fixed x window zooms y onto the visible data.
Range plot_y_range(const PlotSpec& spec, const Range& xr);

/// Linear map between a data axis and pixels; on a log axis the map is linear in log10.
struct AxisMap {
  Range range;
  bool log = false;
  double px_lo = 0.0;  ///< pixel of range.lo (for y: the bottom of the plot area)
  double px_hi = 1.0;  ///< pixel of range.hi
  /// Pixel of data value v; NaN when !axis_valid(v, log).
  double to_px(double v) const;
  /// Data value at pixel p (inverse of to_px).
  double from_px(double p) const;
};

/// One tick mark. Major ticks carry a label; on log axes a decade's label is 10^exponent.
struct Tick {
  double value = 0.0;
  std::string label;  ///< text; for pow10 ticks "10^k" (drawn as 10 with a superscript k)
  bool major = true;
  bool pow10 = false;
  int exponent = 0;
};

/// Smallest 1, 2 or 5 x 10^k that is >= raw (raw > 0).
double nice_step(double raw);

/// Ticks at multiples of a 1-2-5 step, about `target` of them inside [lo, hi].
std::vector<Tick> linear_ticks(double lo, double hi, int target);

/// Log-axis ticks: labelled decades 10^k (every 2nd, 5th, ... decade when there are many, the
/// others unlabelled), minor ticks at 2..9 x 10^k when decades are few; falls back to
/// linear_ticks when the range holds fewer than two decades.
std::vector<Tick> log_ticks(double lo, double hi, int target);

/// linear_ticks or log_ticks for the axis.
std::vector<Tick> axis_ticks(const Range& r, bool log, int target);

/// Label of value v among ticks `step` apart on an axis whose largest |value| is `magnitude`:
/// fixed decimals enough for the step, or d.de±k form for very large or very small numbers.
std::string format_tick(double v, double step, double magnitude);

}  // namespace dampbound::ui
