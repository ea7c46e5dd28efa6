#pragma once
// Progress of a sweep on stderr: a bar redrawn in place on a terminal, plain lines at a
// fixed interval otherwise (logs of batch jobs).
#include <cstdio>

#include "core/sweep_runner.hpp"

namespace dampbound {

class ProgressPrinter {
 public:
  /// `terminal`: redraw one line with '\r'; else print a line every `interval_s` seconds.
  ProgressPrinter(std::FILE* out, bool terminal, double interval_s = 10.0);
  /// Call as often as convenient; prints only when it is time to.
  void update(const SweepProgress& p);

 private:
  std::FILE* out_;
  bool terminal_;
  double interval_s_;
  double last_print_ = -1e30;
  double last_draw_ = -1e30;
};

/// "1h02m", "3m05s", "42s".
std::string format_duration(double seconds);

}  // namespace dampbound
