#include "core/analysis/detail/serial_openmp.hpp"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>

#include "core/analysis/linear_stability_cholesky.hpp"

// libgomp's entry point for `#pragma omp parallel`, as GCC emits it (this file is compiled
// without OpenMP; CHOLMOD loads libgomp).
void gomp_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags) {
  using Parallel = void (*)(void (*)(void*), void*, unsigned, unsigned);
  reinterpret_cast<Parallel>(dlsym(RTLD_DEFAULT, "GOMP_parallel"))(fn, data, num_threads, flags);
}

namespace dampbound::detail {
namespace {

/// What a region's body saw: how many calls, the team's size, the nesting level, and whether
/// it ran on the thread that entered the region.
struct Seen {
  std::atomic<int> calls{0}, team{0}, level{-1}, on_caller{0};
  std::thread::id caller = std::this_thread::get_id();
};
int omp(const char* name) {
  return reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, name))();
}
void body(void* data) {
  auto& seen = *static_cast<Seen*>(data);
  ++seen.calls;
  seen.team = omp("omp_get_num_threads");
  seen.level = omp("omp_get_level");
  if (std::this_thread::get_id() == seen.caller) ++seen.on_caller;
}

// The test binary links CHOLMOD, and Debian's CHOLMOD loads libgomp: the guard must find it.
TEST(SerialOpenMp, FindsTheRuntimeThatCholmodLoads) {
  EXPECT_TRUE(SerialOpenMp::active());
  EXPECT_GE(SerialOpenMp::max_active_levels(), 1);
}

// Core defines no entry point of the OpenMP runtime: the process's GOMP_parallel is libgomp's.
TEST(SerialOpenMp, InterposesNothing) {
  Dl_info info{};
  void* entry = dlsym(RTLD_DEFAULT, "GOMP_parallel");
  ASSERT_NE(entry, nullptr);
  ASSERT_NE(dladdr(entry, &info), 0);
  EXPECT_NE(std::string(info.dli_fname).find("libgomp"), std::string::npos) << info.dli_fname;
}

TEST(SerialOpenMp, SerialInsideTheScopeAndRestoredAfter) {
  const int before = SerialOpenMp::max_active_levels();
  {
    SerialOpenMp outer;
    EXPECT_EQ(SerialOpenMp::max_active_levels(), 0);
    {
      SerialOpenMp inner;  // nested guards restore in order
      EXPECT_EQ(SerialOpenMp::max_active_levels(), 0);
    }
    EXPECT_EQ(SerialOpenMp::max_active_levels(), 0);
  }
  EXPECT_EQ(SerialOpenMp::max_active_levels(), before);
}

TEST(SerialOpenMp, OtherThreadsKeepTheirSetting) {
  const int before = SerialOpenMp::max_active_levels();
  SerialOpenMp guard;
  int seen = -2;
  std::thread other([&] { seen = SerialOpenMp::max_active_levels(); });
  other.join();
  EXPECT_EQ(seen, before);
}

TEST(SerialOpenMp, ARegionUnderTheGuardIsATeamOfOne) {
  Seen seen;
  {
    SerialOpenMp guard;
    gomp_parallel(body, &seen, 4, 0);
  }
  EXPECT_EQ(seen.calls, 1);
  EXPECT_EQ(seen.on_caller, 1);
  EXPECT_EQ(seen.team, 1);
}

// Without the guard a region goes on to libgomp: a user's own OpenMP keeps its threads.
TEST(SerialOpenMp, ARegionWithoutTheGuardGetsItsTeam) {
  Seen seen;
  gomp_parallel(body, &seen, 2, 0);
  EXPECT_EQ(seen.calls, 2);
  EXPECT_EQ(seen.team, 2);
  EXPECT_EQ(seen.level, 1);
}

// Inside a user's region the guard's region is a team of one nested in the user's team.
void outer_body(void* data) {
  SerialOpenMp guard;
  gomp_parallel(body, data, 4, 0);
}
TEST(SerialOpenMp, ARegionInsideAUsersRegionIsATeamOfOne) {
  Seen inner;
  gomp_parallel(outer_body, &inner, 2, 0);
  EXPECT_EQ(inner.calls, 2);  // once per outer thread
  EXPECT_EQ(inner.team, 1);
  EXPECT_EQ(inner.level, 2);
}

// A certified eigenvalue (factorisations, solves) leaves the caller's setting as it was.
TEST(SerialOpenMp, TheCertificateLeavesTheSettingAlone) {
  const int before = SerialOpenMp::max_active_levels();
  const int n = 600;  // above the dense cut-off: CHOLMOD factors it
  SparseMatrix A(n, n);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
  }
  A.setFromTriplets(t.begin(), t.end());
  const EigenInterval top = certified_largest_eigenvalue(A);
  EXPECT_GT(top.factorizations, 0);
  EXPECT_LE(top.lo, 4.0);
  EXPECT_EQ(SerialOpenMp::max_active_levels(), before);
}

}  // namespace
}  // namespace dampbound::detail
