// Progress lines of a sweep (core/sweep/progress.hpp): the rate and the time left follow the
// last five minutes of stepping, not the average since the start.
#include "core/sweep/progress.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

namespace dampbound {
namespace {

/// Everything written to `f` so far, as lines.
std::vector<std::string> lines_of(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::vector<std::string> out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, f)) {
    std::string line(buf);
    if (!line.empty() && line.back() == '\n') line.pop_back();
    out.push_back(line);
  }
  return out;
}

SweepProgress at(double t, std::uint64_t classes) {
  SweepProgress p;
  p.trials_total = p.classes_total = 100000;
  p.classes_resumed = p.trials_resumed = 1000;  // a resumed sweep
  p.classes_done = p.trials_done = classes;
  p.elapsed_s = t;
  return p;
}

TEST(SweepProgress, RateFollowsTheLastMinutesAndSkipsStartUp) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  ProgressPrinter pr(f, false, 60.0);
  // 30 s of start-up (class finding) before the first tick, then 10 classes/s for 600 s,
  // then 40 classes/s (the machine got free) for 600 s.
  std::uint64_t done = 1000;
  double t = 30;
  pr.update(at(t, done));
  for (int k = 0; k < 600; ++k) pr.update(at(t += 1, done += 10));
  for (int k = 0; k < 600; ++k) pr.update(at(t += 1, done += 40));
  SweepProgress last = at(t, done);
  last.final = true;
  pr.update(last);
  const std::vector<std::string> out = lines_of(f);
  std::fclose(f);
  ASSERT_GE(out.size(), 4u);
  // The first line knows no rate yet (the start-up is not stepping).
  EXPECT_NE(out.front().find("? trials/s, ? left"), std::string::npos) << out.front();
  // After 600 s at 10/s: 10 trials/s, and 98000 classes / 10 per s left.
  const std::string& slow = out[10];
  EXPECT_NE(slow.find(" 10 trials/s"), std::string::npos) << slow;
  // 600 s after the change: the five-minute window sees only 40/s (the average since the
  // start would say 25/s).
  const std::string& fast = out[out.size() - 2];
  EXPECT_NE(fast.find(" 40 trials/s"), std::string::npos) << fast;
  EXPECT_NE(fast.find("left"), std::string::npos) << fast;
  // The final line: the whole run's rate (30000 trials in 1230 s) and its time.
  EXPECT_NE(out.back().find(" 24 trials/s, 20m30s elapsed"), std::string::npos) << out.back();
}

TEST(SweepProgress, Durations) {
  EXPECT_EQ(format_duration(42), "42s");
  EXPECT_EQ(format_duration(185), "3m05s");
  EXPECT_EQ(format_duration(3720), "1h02m");
  EXPECT_EQ(format_duration(-1), "?");
}

}  // namespace
}  // namespace dampbound
