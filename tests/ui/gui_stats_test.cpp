// The window's frame statistics (ui/gui_stats.hpp), fed frame times and step counts by hand.
#include "ui/gui_stats.hpp"

#include <gtest/gtest.h>

namespace dampbound::ui {
namespace {

TEST(FrameMeter, FirstFramesSetTheSmoothedValuesThenTheyMoveSlowly) {
  FrameMeter m;
  m.tick(10.0, 0, 0.0);
  EXPECT_EQ(m.stats().frames, 1);
  EXPECT_EQ(m.stats().frame_ms, 0);  // one frame: no interval yet
  m.tick(10.02, 100, 0.005);         // 20 ms, 100 steps, 5 ms stepping
  EXPECT_NEAR(m.stats().frame_ms, 20, 1e-9);
  EXPECT_NEAR(m.stats().steps_per_second, 5000, 1e-6);
  EXPECT_NEAR(m.stats().step_ms, 5, 1e-9);
  m.tick(10.04, 200, 0.010);
  m.tick(10.14, 300, 0.015);  // a slow frame (100 ms) moves the mean by 5 % of the difference
  EXPECT_NEAR(m.stats().frame_ms, 20 + 0.05 * 80, 1e-9);
  EXPECT_EQ(m.stats().frames, 4);
}

TEST(FrameMeter, PausedTheSpeedIsZeroNotATinyNumber) {
  // Paused, the smoothed speed once decayed frame by frame: "speed 6.288e-20 steps/s".
  FrameMeter m;
  double t = 0;
  long long steps = 0;
  for (int k = 0; k < 50; ++k) m.tick(t += 0.02, steps += 100, 0);
  EXPECT_GT(m.stats().steps_per_second, 1000);
  for (int k = 0; k < 900; ++k) m.tick(t += 0.02, steps, 0);
  EXPECT_EQ(m.stats().steps_per_second, 0.0);
}

TEST(FrameMeter, MeasuredSpeedLeavesTheFirstFrameOut) {
  FrameMeter m;
  EXPECT_EQ(m.measured_steps_per_second(), 0);
  m.tick(0.0, 5000, 0);  // start-up: pins run before the first frame
  m.tick(1.0, 5000, 0);  // the second frame starts the measurement
  EXPECT_EQ(m.measured_steps_per_second(), 0);
  m.tick(1.5, 5100, 0);
  m.tick(2.0, 5200, 0);
  EXPECT_NEAR(m.measured_steps_per_second(), 200, 1e-9);  // 200 steps in 1 s
}

}  // namespace
}  // namespace dampbound::ui
