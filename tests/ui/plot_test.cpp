// Pure plot axis maths (ui/plot_math.hpp): ranges, ticks, labels, the data<->pixel map.
// No GL, no ImGui context.
#include "core/physics/detail/numbers.hpp"
#include "ui/plot_math.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dampbound::ui {
namespace {


std::vector<double> values(const std::vector<Tick>& ticks, bool major_only = true) {
  std::vector<double> v;
  for (const auto& t : ticks) {
    if (t.major || !major_only) v.push_back(t.value);
  }
  return v;
}

std::vector<std::string> labels(const std::vector<Tick>& ticks) {
  std::vector<std::string> v;
  for (const auto& t : ticks) {
    if (t.major) v.push_back(t.label);
  }
  return v;
}

TEST(NiceStep, PicksOneTwoFive) {
  EXPECT_DOUBLE_EQ(nice_step(1.0), 1.0);
  EXPECT_DOUBLE_EQ(nice_step(0.2), 0.2);  // 0.2/0.1 is 2.0000000000000004
  EXPECT_DOUBLE_EQ(nice_step(0.3), 0.5);
  EXPECT_DOUBLE_EQ(nice_step(7.0), 10.0);
  EXPECT_DOUBLE_EQ(nice_step(0.0011), 0.002);
  EXPECT_DOUBLE_EQ(nice_step(1234.0), 2000.0);
}

TEST(LinearTicks, UnitRange) {
  const auto t = linear_ticks(0.0, 1.0, 5);
  EXPECT_EQ(labels(t), (std::vector<std::string>{"0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
}

TEST(LinearTicks, ZeroIsNeverNegative) {
  const auto t = linear_ticks(-1.0, 1.0, 4);
  const auto l = labels(t);
  EXPECT_NE(std::find(l.begin(), l.end(), "0"), l.end());
  for (const auto& s : l) EXPECT_NE(s, "-0");
}

TEST(LinearTicks, StayInsideRangeOnMultiplesOfStep) {
  const double ranges[][2] = {{-3.7, 12.2}, {0.0001, 0.1}, {1000.0, 1000.5}, {-1e-7, 3e-7}, {5.0, 1e6}};
  for (const auto& r : ranges) {
    for (int target : {2, 5, 10}) {
      const auto v = values(linear_ticks(r[0], r[1], target));
      ASSERT_GE(v.size(), 2u) << r[0] << " " << r[1];
      EXPECT_LE(static_cast<int>(v.size()), target + 1);
      const double step = v[1] - v[0];
      for (size_t i = 0; i < v.size(); ++i) {
        EXPECT_GE(v[i], r[0] - 1e-12 * std::abs(r[0]));
        EXPECT_LE(v[i], r[1] + 1e-12 * std::abs(r[1]));
        EXPECT_NEAR(v[i] / step, std::round(v[i] / step), 1e-6);
      }
    }
  }
}

TEST(LinearTicks, LabelsForSmallAndLargeNumbers) {
  const auto small = labels(linear_ticks(0.0001, 0.1, 5));
  EXPECT_EQ(small.front(), "0.02");
  const auto tiny = labels(linear_ticks(1e-6, 5e-6, 4));
  EXPECT_EQ(tiny.front(), "1e-6");
  const auto big = labels(linear_ticks(1e5, 2e5, 5));
  EXPECT_NE(std::find(big.begin(), big.end(), "1.2e5"), big.end());
  const auto fine = labels(linear_ticks(1000.0, 1000.5, 5));
  EXPECT_EQ(fine.front(), "1000.0");
}

TEST(FormatTick, Cases) {
  EXPECT_EQ(format_tick(0.0, 0.5, 3.0), "0");
  EXPECT_EQ(format_tick(2.5, 0.5, 3.0), "2.5");
  EXPECT_EQ(format_tick(-3.0, 1.0, 3.0), "-3");
  EXPECT_EQ(format_tick(2e-4, 1e-4, 5e-4), "2e-4");
  EXPECT_EQ(format_tick(3.5e6, 5e5, 4e6), "3.5e6");
}

TEST(LogTicks, DecadesWithMinors) {
  const auto t = log_ticks(1e-4, 1e2, 8);
  const auto major = values(t);
  ASSERT_EQ(major.size(), 7u);
  int k = -4;
  for (const auto& tick : t) {
    if (!tick.major) continue;
    EXPECT_TRUE(tick.pow10);
    EXPECT_EQ(tick.exponent, k);
    EXPECT_EQ(tick.label, "10^" + std::to_string(k));
    EXPECT_NEAR(std::log10(tick.value), k, 1e-12);
    ++k;
  }
  EXPECT_GT(values(t, false).size(), major.size());  // 2..9 x 10^k minors
}

TEST(LogTicks, ManyDecadesAreThinned) {
  const auto t = log_ticks(1e-30, 1e30, 6);
  const auto major = values(t);
  EXPECT_LE(major.size(), 7u);
  EXPECT_GE(major.size(), 2u);
  for (const auto& tick : t) {
    if (tick.major) {
      EXPECT_EQ(tick.exponent % 10, 0);
    }
  }
}

TEST(LogTicks, LessThanTwoDecadesUsesMantissas) {
  const auto t = log_ticks(2.0, 8.0, 10);
  EXPECT_EQ(labels(t), (std::vector<std::string>{"2", "3", "4", "5", "6", "7", "8"}));
  const auto u = log_ticks(0.002, 0.05, 4);  // crowded: label only 1, 2, 5 x 10^k
  for (const auto& tick : u) {
    if (!tick.major) continue;
    const double m = tick.value / std::pow(10.0, std::floor(std::log10(tick.value) + 1e-9));
    EXPECT_TRUE(std::abs(m - 1) < 1e-9 || std::abs(m - 2) < 1e-9 || std::abs(m - 5) < 1e-9) << m;
  }
}

TEST(AxisMap, RoundTripLinearAndLog) {
  const AxisMap lin{{-2.0, 6.0}, false, 100.0, 900.0};
  EXPECT_DOUBLE_EQ(lin.to_px(-2.0), 100.0);
  EXPECT_DOUBLE_EQ(lin.to_px(6.0), 900.0);
  EXPECT_DOUBLE_EQ(lin.to_px(2.0), 500.0);
  const AxisMap lg{{1e-3, 1e3}, true, 600.0, 0.0};  // y: bottom pixel first
  EXPECT_DOUBLE_EQ(lg.to_px(1.0), 300.0);
  for (double v : {1e-3, 0.0123, 1.0, 47.0, 1e3}) {
    EXPECT_NEAR(lin.from_px(lin.to_px(v)), v, 1e-12 * std::max(1.0, std::abs(v)));
    EXPECT_NEAR(lg.from_px(lg.to_px(v)), v, 1e-12 * v);
  }
  EXPECT_TRUE(std::isnan(lin.to_px(kNaN)));
  EXPECT_TRUE(std::isnan(lin.to_px(kInf)));
  EXPECT_TRUE(std::isnan(lg.to_px(0.0)));
  EXPECT_TRUE(std::isnan(lg.to_px(-1.0)));
}

TEST(AutoRange, SkipsNaNInfAndNonPositiveOnLog) {
  const Range r = auto_range({1.0, kNaN, 3.0, kInf, -kInf}, AxisSpec{}, 0.0);
  EXPECT_DOUBLE_EQ(r.lo, 1.0);
  EXPECT_DOUBLE_EQ(r.hi, 3.0);
  AxisSpec log;
  log.log = true;
  const Range l = auto_range({-1.0, 0.0, 10.0, kNaN, 1000.0}, log, 0.0);
  EXPECT_DOUBLE_EQ(l.lo, 10.0);
  EXPECT_DOUBLE_EQ(l.hi, 1000.0);
  const Range padded = auto_range({0.0, 10.0}, AxisSpec{}, 0.05);
  EXPECT_DOUBLE_EQ(padded.lo, -0.5);
  EXPECT_DOUBLE_EQ(padded.hi, 10.5);
}

TEST(AutoRange, EmptyDegenerateAndFixed) {
  const Range e = auto_range({kNaN}, AxisSpec{}, 0.05);
  EXPECT_DOUBLE_EQ(e.lo, 0.0);
  EXPECT_DOUBLE_EQ(e.hi, 1.0);
  const Range one = auto_range({5.0, 5.0}, AxisSpec{}, 0.05);
  EXPECT_LT(one.lo, 5.0);
  EXPECT_GT(one.hi, 5.0);
  AxisSpec fixed;
  fixed.min = 0.0;
  const Range f = auto_range({2.0, 4.0}, fixed, 0.0);
  EXPECT_DOUBLE_EQ(f.lo, 0.0);
  EXPECT_DOUBLE_EQ(f.hi, 4.0);
  fixed.min = 10.0;  // fixed end beyond the data: the other end moves
  const Range g = auto_range({2.0, 4.0}, fixed, 0.0);
  EXPECT_DOUBLE_EQ(g.lo, 10.0);
  EXPECT_GT(g.hi, 10.0);
}

TEST(PlotRange, YFollowsVisibleX) {
  PlotSpec spec;
  PlotSeries s;
  s.x = {0, 1, 2, 3, 4};
  s.y = {100, 1, 2, 3, -50};
  spec.series.push_back(s);
  spec.x.min = 0.5;
  spec.x.max = 3.5;
  const Range xr = plot_x_range(spec);
  EXPECT_DOUBLE_EQ(xr.lo, 0.5);
  const Range yr = plot_y_range(spec, xr);
  EXPECT_LT(yr.lo, 1.0);
  EXPECT_GT(yr.lo, 0.8);
  EXPECT_GT(yr.hi, 3.0);
  EXPECT_LT(yr.hi, 3.2);
}

}  // namespace
}  // namespace dampbound::ui
