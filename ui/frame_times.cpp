#include "ui/frame_times.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dampbound::ui {

FrameTimeSummary summarize_frame_times(const std::vector<double>& frame_ms, int skip) {
  FrameTimeSummary s;
  if (skip < 0) skip = 0;
  if (frame_ms.size() <= static_cast<size_t>(skip)) return s;
  std::vector<double> t(frame_ms.begin() + skip, frame_ms.end());
  std::sort(t.begin(), t.end());
  const size_t n = t.size();
  auto rank = [&](double p) {  // nearest rank, 1-based ceil(p n / 100)
    const size_t r = static_cast<size_t>(std::ceil(p * static_cast<double>(n) / 100.0));
    return t[std::clamp<size_t>(r, 1, n) - 1];
  };
  s.frames = static_cast<int>(n);
  s.mean = std::accumulate(t.begin(), t.end(), 0.0) / static_cast<double>(n);
  s.p50 = rank(50);
  s.p99 = rank(99);
  s.max = t.back();
  return s;
}

}  // namespace dampbound::ui
