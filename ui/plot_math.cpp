#include "ui/plot_math.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace dampbound::ui {

namespace {
/// Values beyond this are treated as invalid for ranges: their span would overflow.
constexpr double kHuge = 1e300;
constexpr double kEps = 1e-9;

double to_axis(double v, bool log) { return log ? std::log10(v) : v; }
double from_axis(double u, bool log) { return log ? std::pow(10.0, u) : u; }
}  // namespace

bool axis_valid(double v, bool log) { return std::isfinite(v) && (!log || v > 0.0); }

void RangeAccumulator::add(double v) {
  if (!axis_valid(v, log_) || std::abs(v) > kHuge) return;
  if (n_ == 0) {
    lo_ = hi_ = v;
  } else {
    lo_ = std::min(lo_, v);
    hi_ = std::max(hi_, v);
  }
  ++n_;
}

void RangeAccumulator::add(const std::vector<double>& values) {
  for (double v : values) add(v);
}

Range finish_range(const RangeAccumulator& acc, const AxisSpec& axis, double pad) {
  const bool log = axis.log;
  // Without data: [0, 1], or [1, 10] on a log axis (0 and 1 in log10 units).
  double a = acc.empty() ? 0.0 : to_axis(acc.lo(), log);
  double b = acc.empty() ? 1.0 : to_axis(acc.hi(), log);
  if (!(b > a)) {
    // One distinct value: half a decade either side, or 10 % of the value (0.5 around 0).
    const double w = log ? 0.5 : (a == 0.0 ? 0.5 : std::abs(a) * 0.1);
    a -= w;
    b += w;
  } else if (!acc.empty() && pad > 0.0 && std::isfinite(b - a)) {
    const double s = (b - a) * pad;
    a -= s;
    b += s;
  }
  Range r{from_axis(a, log), from_axis(b, log)};
  const bool fix_lo = axis.min.has_value() && axis_valid(*axis.min, log);
  const bool fix_hi = axis.max.has_value() && axis_valid(*axis.max, log);
  if (fix_lo) r.lo = *axis.min;
  if (fix_hi) r.hi = *axis.max;
  if (!(r.hi > r.lo)) {
    if (fix_lo && fix_hi) std::swap(r.lo, r.hi);
    // A fixed end beyond all the data, or equal fixed ends: keep the fixed end, widen the other.
    if (!(r.hi > r.lo)) {
      const double w = log ? 1.0 : std::max(std::abs(fix_lo ? r.lo : r.hi), 1.0);
      if (fix_hi && !fix_lo) {
        r.lo = from_axis(to_axis(r.hi, log) - w, log);
      } else {
        r.hi = from_axis(to_axis(r.lo, log) + w, log);
      }
    }
  }
  return r;
}

Range auto_range(const std::vector<double>& values, const AxisSpec& axis, double pad) {
  RangeAccumulator acc(axis.log);
  acc.add(values);
  return finish_range(acc, axis, pad);
}

namespace {
/// Heat maps fill the plot edge to edge; without one the data gets a 5 % margin.
double default_pad(const PlotSpec& spec) { return spec.heatmap.empty() ? 0.05 : 0.0; }
}  // namespace

Range plot_x_range(const PlotSpec& spec) {
  RangeAccumulator acc(spec.x.log);
  for (const auto& s : spec.series) {
    const size_t n = std::min(s.x.size(), s.y.size());
    for (size_t i = 0; i < n; ++i) {
      if (axis_valid(s.y[i], spec.y.log)) acc.add(s.x[i]);
    }
  }
  for (const auto& b : spec.bands) acc.add(b.x);
  for (const PlotRefLine& l : spec.ref_lines)
    if (l.axis == LineAxis::x) acc.add(l.at);
  if (!spec.heatmap.empty()) {
    acc.add(spec.heatmap.x_edges.front());
    acc.add(spec.heatmap.x_edges.back());
  }
  return finish_range(acc, spec.x, default_pad(spec));
}

Range plot_y_range(const PlotSpec& spec, const Range& xr) {
  const bool xlog = spec.x.log;
  auto in_x = [&](double x) { return axis_valid(x, xlog) && x >= xr.lo && x <= xr.hi; };
  RangeAccumulator acc(spec.y.log);
  for (const auto& s : spec.series) {
    const size_t n = std::min(s.x.size(), s.y.size());
    for (size_t i = 0; i < n; ++i) {
      if (in_x(s.x[i])) acc.add(s.y[i]);
    }
  }
  for (const auto& b : spec.bands) {
    const size_t n = std::min({b.x.size(), b.y_lo.size(), b.y_hi.size()});
    for (size_t i = 0; i < n; ++i) {
      if (!in_x(b.x[i])) continue;
      acc.add(b.y_lo[i]);  // infinite ends are skipped: they mean "to the plot edge"
      acc.add(b.y_hi[i]);
    }
  }
  for (const PlotRefLine& l : spec.ref_lines)
    if (l.axis == LineAxis::y) acc.add(l.at);
  if (!spec.heatmap.empty()) {
    acc.add(spec.heatmap.y_edges.front());
    acc.add(spec.heatmap.y_edges.back());
  }
  return finish_range(acc, spec.y, default_pad(spec));
}

double AxisMap::to_px(double v) const {
  if (!axis_valid(v, log)) return std::numeric_limits<double>::quiet_NaN();
  const double a = to_axis(range.lo, log);
  const double b = to_axis(range.hi, log);
  const double t = (to_axis(v, log) - a) / (b - a);
  return px_lo + t * (px_hi - px_lo);
}

double AxisMap::from_px(double p) const {
  const double a = to_axis(range.lo, log);
  const double b = to_axis(range.hi, log);
  const double t = (p - px_lo) / (px_hi - px_lo);
  return from_axis(a + t * (b - a), log);
}

double nice_step(double raw) {
  if (!(raw > 0.0) || !std::isfinite(raw)) return 1.0;
  const double base = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / base;
  // Tolerances absorb rounding: 0.2 / 0.1 is 2.0000000000000004.
  const double m = f <= 1.0 + kEps ? 1.0 : f <= 2.0 + kEps ? 2.0 : f <= 5.0 + kEps ? 5.0 : 10.0;
  return m * base;
}

std::string format_tick(double v, double step, double magnitude) {
  if (v == 0.0 || std::abs(v) < std::abs(step) * 1e-6) return "0";
  const int step_exp = static_cast<int>(std::floor(std::log10(std::abs(step)) + kEps));
  char buf[64];
  if (magnitude >= 1e5 || magnitude < 1e-3) {
    const int val_exp = static_cast<int>(std::floor(std::log10(std::abs(v)) + kEps));
    const int digits = std::clamp(val_exp - step_exp, 0, 12);
    std::snprintf(buf, sizeof buf, "%.*e", digits, v);
    // 1.5e+05 -> 1.5e5, 2e-04 -> 2e-4
    std::string s(buf);
    const size_t e = s.find('e');
    if (e == std::string::npos) return s;
    std::string mant = s.substr(0, e);
    std::string ex = s.substr(e + 1);
    const bool neg = !ex.empty() && ex[0] == '-';
    if (!ex.empty() && (ex[0] == '+' || ex[0] == '-')) ex.erase(0, 1);
    ex.erase(0, std::min(ex.find_first_not_of('0'), ex.size() - 1));
    return mant + "e" + (neg ? "-" : "") + ex;
  }
  const int decimals = std::clamp(-step_exp, 0, 12);
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::vector<Tick> linear_ticks(double lo, double hi, int target) {
  std::vector<Tick> ticks;
  const double span = hi - lo;
  if (!(span > 0.0) || !std::isfinite(span)) return ticks;
  const double step = nice_step(span / std::max(target, 2));
  const double magnitude = std::max(std::abs(lo), std::abs(hi));
  const double first = std::ceil(lo / step - kEps);
  for (int k = 0; k < 1000; ++k) {
    double v = (first + k) * step;
    if (v > hi + step * kEps) break;
    if (std::abs(v) < step * 1e-9) v = 0.0;
    ticks.push_back({v, format_tick(v, step, magnitude), true, false, 0});
  }
  return ticks;
}

std::vector<Tick> log_ticks(double lo, double hi, int target) {
  std::vector<Tick> ticks;
  if (!(lo > 0.0) || !(hi > lo) || !std::isfinite(hi)) return ticks;
  target = std::max(target, 2);
  const double a = std::log10(lo), b = std::log10(hi);
  const int k0 = static_cast<int>(std::ceil(a - kEps));
  const int k1 = static_cast<int>(std::floor(b + kEps));
  const int n = k1 - k0 + 1;
  auto inside = [&](double v) { return v >= lo * (1 - kEps) && v <= hi * (1 + kEps); };
  if (n < 2) {
    // Less than two decades visible: 1..9 x 10^k, labelled at 1, 2, 5 when crowded.
    std::vector<double> vals;
    for (int k = k0 - 1; k <= k1; ++k) {
      for (int m = 1; m <= 9; ++m) {
        const double v = m * std::pow(10.0, k);
        if (inside(v)) vals.push_back(v);
      }
    }
    const bool crowded = static_cast<int>(vals.size()) > target;
    for (double v : vals) {
      const double decade = std::pow(10.0, std::floor(std::log10(v) + kEps));
      const int m = static_cast<int>(std::lround(v / decade));
      const bool labelled = !crowded || m == 1 || m == 2 || m == 5;
      ticks.push_back({v, labelled ? format_tick(v, decade, hi) : "", labelled, false, 0});
    }
    if (ticks.size() < 2) return linear_ticks(lo, hi, target);
    return ticks;
  }
  int every = 1;
  static const int kSteps[] = {1, 2, 5, 10, 20, 50, 100};
  for (int s : kSteps) {
    every = s;
    if (n / s <= target) break;
  }
  for (int k = k0; k <= k1; ++k) {
    const bool major = ((k % every) + every) % every == 0;
    Tick t{std::pow(10.0, k), "", major, major, k};
    if (major) t.label = "10^" + std::to_string(k);
    ticks.push_back(t);
  }
  if (every == 1 && n <= 2 * target) {
    for (int k = k0 - 1; k <= k1; ++k) {
      for (int m = 2; m <= 9; ++m) {
        const double v = m * std::pow(10.0, k);
        if (inside(v)) ticks.push_back({v, "", false, false, 0});
      }
    }
    std::sort(ticks.begin(), ticks.end(),
              [](const Tick& p, const Tick& q) { return p.value < q.value; });
  }
  return ticks;
}

std::vector<Tick> axis_ticks(const Range& r, bool log, int target) {
  return log ? log_ticks(r.lo, r.hi, target) : linear_ticks(r.lo, r.hi, target);
}

}  // namespace dampbound::ui
