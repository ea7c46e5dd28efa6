// The node threads: chunks cover [0, n) exactly once, small loops stay on the caller's
// thread, and a copy gets threads of its own.
#include "dampbound/physics/node_threads.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace dampbound {
namespace {

TEST(NodeThreads, ChunksCoverTheRangeOnceInOrder) {
  for (int threads : {1, 2, 3, 8}) {
    NodeThreads pool(threads);
    pool.set_grain(1000);
    for (size_t n : {size_t(0), size_t(5), size_t(4095), size_t(4096), size_t(100003)}) {
      const int chunks = pool.chunks(n);
      ASSERT_GE(chunks, 1);
      ASSERT_LE(chunks, threads);
      std::vector<int> hits(n, 0);
      std::vector<size_t> begin(static_cast<size_t>(chunks)), end(begin.size());
      pool.run(n, [&](int c, size_t b, size_t e) {
        begin[static_cast<size_t>(c)] = b;
        end[static_cast<size_t>(c)] = e;
        for (size_t i = b; i < e; ++i) ++hits[i];
      });
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(hits[i], 1) << threads << " " << n << " " << i;
      for (int c = 0; c + 1 < chunks; ++c) EXPECT_EQ(end[size_t(c)], begin[size_t(c) + 1]);
      EXPECT_EQ(begin.front(), 0u);
      EXPECT_EQ(end.back(), n);
    }
  }
}

TEST(NodeThreads, SmallLoopsStayOnTheCallersThread) {
  NodeThreads pool(4);
  EXPECT_EQ(pool.chunks(NodeThreads::kMinItemsPerThread - 1), 1);
  EXPECT_EQ(pool.chunks(2 * NodeThreads::kMinItemsPerThread), 2);
  EXPECT_EQ(pool.chunks(100 * NodeThreads::kMinItemsPerThread), 4);
  const auto caller = std::this_thread::get_id();
  bool same = false;
  pool.run(100, [&](int, size_t, size_t) { same = std::this_thread::get_id() == caller; });
  EXPECT_TRUE(same);
}

TEST(NodeThreads, LargeLoopsRunOnOtherThreadsTooAndManyTimes) {
  NodeThreads pool(3);
  const size_t n = 3 * NodeThreads::kMinItemsPerThread;
  for (int round = 0; round < 200; ++round) {  // the pool is reused, never re-created
    std::atomic<int> others{0};
    std::atomic<size_t> total{0};
    const auto caller = std::this_thread::get_id();
    pool.run(n, [&](int, size_t b, size_t e) {
      if (std::this_thread::get_id() != caller) ++others;
      total += e - b;
    });
    ASSERT_EQ(others.load(), 2);
    ASSERT_EQ(total.load(), n);
  }
}

// Polling threads (Lanczos's products) run every loop once: loops back to back, loops that
// need fewer threads than the pool has, and loops after a pause longer than the polling, when
// the threads have gone to sleep.
TEST(NodeThreads, PollingThreadsRunEveryLoopOnce) {
  NodeThreads pool(3);
  pool.set_spin_microseconds(200);
  const size_t big = 3 * NodeThreads::kMinItemsPerThread,
               small = 2 * NodeThreads::kMinItemsPerThread;
  for (int round = 0; round < 300; ++round) {
    const size_t n = round % 3 == 2 ? small : big;
    std::atomic<size_t> total{0};
    std::atomic<int> calls{0};
    pool.run(n, [&](int, size_t b, size_t e) {
      total += e - b;
      ++calls;
    });
    ASSERT_EQ(total.load(), n);
    ASSERT_EQ(calls.load(), pool.chunks(n));
    if (round % 50 == 49) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  NodeThreads copy = pool;
  EXPECT_EQ(copy.spin_microseconds(), 200);
  NodeThreads assigned;
  assigned = pool;
  EXPECT_EQ(assigned.spin_microseconds(), 200);
}

TEST(NodeThreads, CopiesKeepTheCountAndZeroMeansTheHardware) {
  NodeThreads a(3);
  NodeThreads b = a;
  EXPECT_EQ(b.threads(), 3);
  NodeThreads c;
  EXPECT_EQ(c.threads(), 1);
  c = a;
  EXPECT_EQ(c.threads(), 3);
  c.set_threads(0);
  EXPECT_EQ(c.threads(), static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
}

}  // namespace
}  // namespace dampbound
