// Tests of core/analysis/detail/beside: the thread count a `threads` argument resolves to,
// Beside's work on a thread of its own (done, failed, finish rethrowing, the destructor
// joining), and the Lanczos estimate beside it giving the bits of one thread and stopping
// when asked.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/beside.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "tests/core/analysis/detail/factor_matrices.hpp"

namespace dampbound::detail {
namespace {

TEST(Beside, ThreadsResolveToTheCountGivenOrOnePerCpu) {
  EXPECT_EQ(resolved_threads(1), 1);
  EXPECT_EQ(resolved_threads(5), 5);
  const int cpus = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  EXPECT_EQ(resolved_threads(0), cpus);
  EXPECT_EQ(resolved_threads(-3), cpus);
}

TEST(Beside, WorkRunsOnItsOwnThreadAndFinishJoinsIt) {
  std::atomic<bool> go{false};
  std::thread::id worker;
  Beside b([&] {
    while (!go.load()) std::this_thread::yield();
    worker = std::this_thread::get_id();
  });
  EXPECT_FALSE(b.done());  // it waits for go
  go = true;
  b.finish();
  EXPECT_TRUE(b.done());
  EXPECT_FALSE(b.failed());
  EXPECT_NE(worker, std::this_thread::get_id());
}

TEST(Beside, FinishRethrowsWhatTheWorkThrew) {
  Beside b([] { throw std::runtime_error("from beside"); });
  while (!b.done()) std::this_thread::yield();
  EXPECT_TRUE(b.failed());
  try {
    b.finish();
    FAIL() << "finish() must rethrow";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "from beside");
  }
}

TEST(Beside, TheDestructorJoinsWorkNotFinished) {
  std::atomic<int> ran{0};
  {
    Beside b([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      ran = 1;
    });
  }
  EXPECT_EQ(ran.load(), 1);
}

TEST(Beside, TheEstimateBesideGivesTheBitsOfOneThreadAndStopsWhenAsked) {
  const SparseMatrix A = test::deformed_plane(12);
  LanczosRecurrence<float> alone(A, 1);
  const TopEstimate expected = lanczos_estimate(alone, A.rows());
  int calls = 0;
  // The thread beside finishes after 30 steps: from then on all cores.
  const TopEstimate e = estimate_beside(
      A, 3, [&] { return ++calls > 30; }, [] { return false; });
  EXPECT_EQ(e.alpha, expected.alpha);
  EXPECT_EQ(e.beta, expected.beta);
  EXPECT_EQ(e.theta, expected.theta);
  EXPECT_EQ(e.steps, expected.steps);
  EXPECT_GT(calls, 30);
  int steps = 0;
  const TopEstimate stopped = estimate_beside(
      A, 2, [] { return false; }, [&] { return ++steps > 5; });
  EXPECT_EQ(stopped.steps, 6);  // stop() is asked after each step
  EXPECT_EQ(stopped.alpha, std::vector<double>(expected.alpha.begin(), expected.alpha.begin() + 6));
}

}  // namespace
}  // namespace dampbound::detail
