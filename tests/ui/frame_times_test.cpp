// Frame-time statistics of `dampbound gui --stats` (ui/frame_times.hpp): the startup frame is
// left out, percentiles by nearest rank.
#include "ui/frame_times.hpp"

#include <gtest/gtest.h>

namespace dampbound::ui {
namespace {

TEST(FrameTimes, SkipsStartupAndTakesNearestRanks) {
  std::vector<double> ms = {11000.0};  // the first frame: fonts, layout, first analysis
  for (int k = 1; k <= 100; ++k) ms.push_back(k);  // 1 .. 100 ms, in order
  const FrameTimeSummary s = summarize_frame_times(ms, 1);
  EXPECT_EQ(s.frames, 100);
  EXPECT_DOUBLE_EQ(s.mean, 50.5);
  EXPECT_DOUBLE_EQ(s.p50, 50);  // ceil(0.50 * 100) = 50th smallest
  EXPECT_DOUBLE_EQ(s.p99, 99);  // ceil(0.99 * 100) = 99th smallest
  EXPECT_DOUBLE_EQ(s.max, 100);
  const FrameTimeSummary all = summarize_frame_times(ms, 0);
  EXPECT_DOUBLE_EQ(all.max, 11000.0);
  EXPECT_DOUBLE_EQ(all.p50, 51);  // ceil(0.5 * 101) = 51st smallest of 1..100, 11000
}

TEST(FrameTimes, FewOrNoFrames) {
  EXPECT_EQ(summarize_frame_times({}, 1).frames, 0);
  EXPECT_EQ(summarize_frame_times({5.0}, 1).frames, 0);
  const FrameTimeSummary two = summarize_frame_times({9.0, 3.0, 7.0}, 1);
  EXPECT_EQ(two.frames, 2);
  EXPECT_DOUBLE_EQ(two.p50, 3.0);
  EXPECT_DOUBLE_EQ(two.p99, 7.0);
  EXPECT_DOUBLE_EQ(two.mean, 5.0);
}

}  // namespace
}  // namespace dampbound::ui
