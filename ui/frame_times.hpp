#pragma once
// Frame-time statistics of a window run (`dampbound gui --stats`): mean, median, 99th
// percentile and maximum, without the startup frames.
#include <vector>

namespace dampbound::ui {

/// Summary of frame times (milliseconds) over the frames that count.
struct FrameTimeSummary {
  int frames = 0;     ///< frames summarised (after the skipped ones)
  double mean = 0;    ///< ms
  double p50 = 0;     ///< ms, nearest-rank median
  double p99 = 0;     ///< ms, nearest-rank 99th percentile
  double max = 0;     ///< ms
};

/// Summarises frame_ms[skip..]: the first `skip` frames (startup: fonts, first layout, first
/// analysis) are left out. Nearest rank: the p-th percentile is the ceil(p N / 100)-th
/// smallest. All zero when nothing is left.
FrameTimeSummary summarize_frame_times(const std::vector<double>& frame_ms, int skip = 1);

}  // namespace dampbound::ui
