// The tuner's background work (Suggest here; the exact analysis and the Map start their
// threads the same way) runs at the frames' priority: at nice 19 it starved on a busy
// machine (Suggest 15-45 s, the Map 63-86 s) while a person waited for it.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>

#include <unistd.h>

#include "core/io/scene_file.hpp"
#include "ui/tuner.hpp"
#include "ui/tuner_criteria.hpp"

namespace dampbound::ui {
namespace {

/// The nice value of every thread of this process by thread id (the 19th field of
/// /proc/self/task/TID/stat).
std::map<std::string, int> thread_nices() {
  std::map<std::string, int> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream in(e.path() / "stat");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t close = text.rfind(')');  // the name may hold blanks
    if (close == std::string::npos) continue;
    std::istringstream f(text.substr(close + 2));
    std::string field;
    for (int k = 3; k <= 19 && f >> field; ++k)
      if (k == 19) out[e.path().filename().string()] = std::stoi(field);
  }
  return out;
}

TEST(WorkerPriority, SuggestRunsAtTheFramesPriority) {
  if (!std::filesystem::exists("/proc/self/task")) GTEST_SKIP() << "no /proc";
  // The threads there before (other tests' pools) are not looked at.
  const std::map<std::string, int> before = thread_nices();
  ASSERT_EQ(before.count(std::to_string(getpid())), 1u);
  const int frames = before.at(std::to_string(getpid()));
  Tuner t(load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/paper-plane.toml"));
  TunerSuggest s;
  s.start(t.session());
  int samples = 0, lowered = 0;
  while (s.busy() && !s.poll()) {
    for (const auto& [tid, nice] : thread_nices()) lowered += !before.count(tid) && nice != frames;
    ++samples;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_GT(samples, 0);
  EXPECT_EQ(lowered, 0) << "a worker thread ran at another nice value than the frames'";
  EXPECT_TRUE(s.result().has_value()) << s.error();
}

TEST(TunerSuggestCancel, DropsTheComputationAtOnceAndKeepsTheLastResult) {
  Tuner t(load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/paper-plane.toml"));
  TunerSuggest s;
  s.start(t.session());
  ASSERT_TRUE(s.busy());
  const auto t0 = std::chrono::steady_clock::now();
  s.cancel();
  EXPECT_FALSE(s.poll());
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(ms, 50.0) << "cancel waited for the worker";
  EXPECT_FALSE(s.busy());
  EXPECT_TRUE(s.cancelled());
  EXPECT_FALSE(s.result().has_value());
  s.start(t.session());  // a new one runs to its end
  s.wait();
  EXPECT_FALSE(s.cancelled());
  EXPECT_TRUE(s.result().has_value()) << s.error();
}

}  // namespace
}  // namespace dampbound::ui
