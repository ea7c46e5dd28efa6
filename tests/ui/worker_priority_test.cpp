// The tuner's workers run below the frames' priority, and the threads they start inherit it
// (ui/worker_priority.hpp).
#include "ui/worker_priority.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace dampbound::ui {
namespace {

TEST(WorkerPriority, AWorkerAndTheThreadsItStartsRunBelowTheFramesAndTheCallerKeepsItsOwn) {
  const int frames = worker_nice();
  int worker = 0, child = 0;
  bool lowered = false;
  std::thread t([&] {
    lowered = lower_worker_priority();
    worker = worker_nice();
    std::thread c([&] { child = worker_nice(); });
    c.join();
  });
  t.join();
  ASSERT_TRUE(lowered);
  EXPECT_GE(worker, kWorkerNice);
  EXPECT_GE(worker, frames);
  EXPECT_EQ(child, worker);
  EXPECT_EQ(worker_nice(), frames);  // only the worker's thread changed
}

}  // namespace
}  // namespace dampbound::ui
