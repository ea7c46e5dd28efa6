// Pure pixel geometry (ui/plot_geometry.hpp): clipping, polylines with gaps, min/max
// decimation of series and bands, dashes. No GL, no ImGui context.
#include "core/physics/detail/numbers.hpp"
#include "ui/plot_geometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dampbound::ui {
namespace {


TEST(ClipSegment, LiangBarsky) {
  const PixelRect r{0, 0, 10, 10};
  double ax = -5, ay = 5, bx = 15, by = 5;
  ASSERT_TRUE(clip_segment(ax, ay, bx, by, r));
  EXPECT_DOUBLE_EQ(ax, 0.0);
  EXPECT_DOUBLE_EQ(bx, 10.0);
  double cx = -5, cy = -5, dx = -1, dy = 20;
  EXPECT_FALSE(clip_segment(cx, cy, dx, dy, r));
}

TEST(ProjectPolylines, NaNBreaksAndClipping) {
  const AxisMap mx{{0, 10}, false, 0, 100};
  const AxisMap my{{0, 10}, false, 100, 0};
  const PixelRect clip{0, 0, 100, 100};
  const auto lines = project_polylines({0, 1, 2, 3, 4, 5}, {1, 2, kNaN, 4, 5, 6}, mx, my, clip);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].size(), 2u);
  EXPECT_EQ(lines[1].size(), 3u);
  EXPECT_FLOAT_EQ(lines[1][0].x, 30.0f);
  EXPECT_FLOAT_EQ(lines[1][0].y, 60.0f);
  // Leaves the top at x = 5, comes back: two pieces, ends on the border.
  const auto out = project_polylines({0, 5, 10, 15, 20}, {5, 15, 15, 5, 5}, mx, my, clip);
  ASSERT_EQ(out.size(), 1u);  // the returning part starts at x = 15 > 10: outside
  EXPECT_FLOAT_EQ(out[0].back().y, 0.0f);
  EXPECT_FLOAT_EQ(out[0].back().x, 25.0f);
}

TEST(Decimate, KeepsExtremesAndEnds) {
  std::vector<ImVec2> pts;
  const int n = 10000;
  for (int i = 0; i < n; ++i) {
    const float x = 10.0f + 500.0f * static_cast<float>(i) / n;  // 20 points per column
    pts.emplace_back(x, 300.0f + 100.0f * std::sin(static_cast<float>(i) * 0.37f));
  }
  pts[4321].y = -1000.0f;  // spikes must survive
  pts[7777].y = 2000.0f;
  const auto d = decimate_columns(pts);
  EXPECT_LE(d.size(), 4u * 501u);
  EXPECT_LT(d.size(), pts.size() / 4);
  EXPECT_FLOAT_EQ(d.front().x, pts.front().x);
  EXPECT_FLOAT_EQ(d.back().x, pts.back().x);
  auto lowest = std::min_element(d.begin(), d.end(), [](auto a, auto b) { return a.y < b.y; });
  auto highest = std::max_element(d.begin(), d.end(), [](auto a, auto b) { return a.y < b.y; });
  EXPECT_FLOAT_EQ(lowest->y, -1000.0f);
  EXPECT_FLOAT_EQ(highest->y, 2000.0f);
  // Every column's min and max survive, and x never goes backwards.
  for (size_t i = 1; i < d.size(); ++i) EXPECT_GE(d[i].x, d[i - 1].x);
}

TEST(Decimate, BandColumnEnvelopeKeepsSpikesAndEmptiness) {
  std::vector<BandSample> in;
  for (int i = 0; i < 100; ++i) {  // 20 samples per pixel column, columns 10..14
    const double x = 10.0 + i * 0.05;
    in.push_back({x, 200.0, 100.0 + (i % 7)});
  }
  in[47].hi = -5.0;                     // a spike to the top in column 12
  for (int i = 80; i < 100; ++i) in[static_cast<size_t>(i)].lo = 50.0;  // column 14: empty (lo above hi)
  const auto out = decimate_band_columns(in);
  ASSERT_EQ(out.size(), 10u);  // first and last x of each column
  EXPECT_DOUBLE_EQ(out[0].x, in[0].x);
  EXPECT_DOUBLE_EQ(out[1].x, in[19].x);
  EXPECT_DOUBLE_EQ(out[0].hi, 100.0);   // highest upper curve on screen (smallest y)
  EXPECT_DOUBLE_EQ(out[0].lo, 200.0);
  EXPECT_DOUBLE_EQ(out[4].hi, -5.0);    // the spike survives
  EXPECT_LT(out[8].lo, out[8].hi);      // still empty
  EXPECT_LT(out[9].lo, out[9].hi);
  // A gap stays a gap.
  in[30].x = kNaN;
  const auto gap = decimate_band_columns(in);
  EXPECT_TRUE(std::any_of(gap.begin(), gap.end(), [](const BandSample& b) { return std::isnan(b.x); }));
}

TEST(ClipPolygon, SquareAgainstRect) {
  const auto p = clip_polygon({{-5, -5}, {5, -5}, {5, 5}, {-5, 5}}, PixelRect{0, 0, 10, 10});
  ASSERT_GE(p.size(), 4u);
  for (const auto& v : p) {
    EXPECT_GE(v.x, 0.0f);
    EXPECT_GE(v.y, 0.0f);
    EXPECT_LE(v.x, 5.0f);
    EXPECT_LE(v.y, 5.0f);
  }
  EXPECT_TRUE(clip_polygon({{20, 20}, {30, 20}, {30, 30}}, PixelRect{0, 0, 10, 10}).empty());
}

TEST(Polyline, SharpTurnsSplitAndDashes) {
  const auto runs = split_sharp_turns({{0, 0}, {10, 0}, {0, 1}, {10, 2}});
  EXPECT_EQ(runs.size(), 3u);
  const auto smooth = split_sharp_turns({{0, 0}, {10, 0}, {20, 5}, {30, 5}});
  EXPECT_EQ(smooth.size(), 1u);
  const auto dashes = dash_polyline({{0, 0}, {100, 0}}, 10.0f, 5.0f);
  EXPECT_EQ(dashes.size(), 7u);  // 0-10, 15-25, ..., 90-100
  float on = 0.0f;
  for (const auto& d : dashes) on += d.back().x - d.front().x;
  EXPECT_NEAR(on, 70.0f, 1e-3f);
}

}  // namespace
}  // namespace dampbound::ui
