#pragma once
// Progress of a sweep on stderr: a bar redrawn in place on a terminal, plain lines at a
// fixed interval otherwise (logs of batch jobs).
#include <cstdint>
#include <cstdio>
#include <deque>
#include <string>

#include "core/sweep/runner.hpp"

namespace dampbound {

class ProgressPrinter {
 public:
  /// `terminal`: redraw one line with '\r'; else print a line every `interval_s` seconds.
  ProgressPrinter(std::FILE* out, bool terminal, double interval_s = 10.0);
  /// Call as often as convenient; prints only when it is time to. The rate and the time left
  /// are measured over the last five minutes of stepping (start-up excluded), so they follow
  /// a change of load; the final line gives the whole run's rate and time.
  void update(const SweepProgress& p);

 private:
  struct Sample {
    double t;
    std::uint64_t classes, trials;
  };
  std::deque<Sample> window_;  ///< about one sample a second, the last five minutes
  std::FILE* out_;
  bool terminal_;
  double interval_s_;
  double last_print_ = -1e30;
  double last_draw_ = -1e30;
};

/// "1h02m", "3m05s", "42s".
std::string format_duration(double seconds);

}  // namespace dampbound
