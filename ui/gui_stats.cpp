#include "ui/gui_stats.hpp"

namespace dampbound::ui {

void FrameMeter::tick(double t, long long steps, double step_s) {
  if (last_time_ >= 0) {
    const double dt = t - last_time_;
    const double a = stats_.frames < 3 ? 1.0 : 0.05;  // smoothing over ~20 frames
    stats_.frame_ms += a * (dt * 1e3 - stats_.frame_ms);
    if (dt > 0) {
      // A frame without steps (paused) says 0: the smoothed value would only decay towards it.
      const double sps = static_cast<double>(steps - last_steps_) / dt;
      stats_.steps_per_second =
          steps == last_steps_ ? 0.0 : stats_.steps_per_second + a * (sps - stats_.steps_per_second);
    }
    stats_.step_ms += a * ((step_s - last_step_seconds_) * 1e3 - stats_.step_ms);
  }
  if (stats_.frames == 1) {  // the second frame starts: the start-up is over
    run_start_time_ = t;
    run_start_steps_ = steps;
  }
  last_time_ = t;
  last_steps_ = steps;
  last_step_seconds_ = step_s;
  ++stats_.frames;
}

double FrameMeter::measured_steps_per_second() const {
  if (run_start_time_ < 0 || !(last_time_ > run_start_time_)) return 0;
  return static_cast<double>(last_steps_ - run_start_steps_) / (last_time_ - run_start_time_);
}

}  // namespace dampbound::ui
