#pragma once
// The tuner window's frame statistics: frame time and stepping speed, smoothed over about
// 20 frames, and the speed measured over the whole run without the start-up frame.
// No GL, no ImGui (tests/ui/gui_stats_test.cpp).

namespace dampbound::ui {

/// Frame statistics of the window.
struct GuiStats {
  int frames = 0;
  double frame_ms = 0;          ///< smoothed wall time between frames
  double steps_per_second = 0;  ///< smoothed; 0 after a frame without steps
  double step_ms = 0;           ///< smoothed time in step() per frame
};

/// Feeds GuiStats one frame at a time.
class FrameMeter {
 public:
  /// A frame starts at `now_s` (seconds, any fixed origin) with `steps` steps taken in all
  /// and `step_seconds` spent in step() in all.
  void tick(double now_s, long long steps, double step_seconds);
  const GuiStats& stats() const { return stats_; }
  /// Steps per second from the start of the second frame to the last one: the start-up
  /// (first frame, pins run before it) left out. 0 before the third frame.
  double measured_steps_per_second() const;

 private:
  GuiStats stats_;
  double last_time_ = -1;  ///< s, start of the last frame
  long long last_steps_ = 0;
  double last_step_seconds_ = 0;  ///< s
  double run_start_time_ = -1;    ///< s, start of the second frame
  long long run_start_steps_ = 0;
};

}  // namespace dampbound::ui
