#include "core/analysis/detail/serial_openmp.hpp"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "core/analysis/linear_stability_cholesky.hpp"

// libgomp's entry point for `#pragma omp parallel`, as GCC emits it; core defines it
// (serial_openmp.cpp).
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags);

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

TEST(SerialOpenMp, ARegionUnderTheGuardIsAPlainCall) {
  const long before = SerialOpenMp::inline_regions();
  Seen seen;
  {
    SerialOpenMp guard;
    GOMP_parallel(body, &seen, 4, 0);
  }
  EXPECT_EQ(seen.calls, 1);
  EXPECT_EQ(seen.on_caller, 1);
  EXPECT_EQ(seen.team, 1);   // what a team of one shows its body
  EXPECT_EQ(seen.level, 0);  // no team was made
  EXPECT_EQ(SerialOpenMp::inline_regions(), before + 1);
}

// Without the guard a region goes on to libgomp: a user's own OpenMP keeps its threads.
TEST(SerialOpenMp, ARegionWithoutTheGuardGetsItsTeam) {
  const long before = SerialOpenMp::inline_regions();
  Seen seen;
  GOMP_parallel(body, &seen, 2, 0);
  EXPECT_EQ(seen.calls, 2);
  EXPECT_EQ(seen.team, 2);
  EXPECT_EQ(seen.level, 1);
  EXPECT_EQ(SerialOpenMp::inline_regions(), before);
}

// Inside a user's region a plain call would let the body see the outer team (its size and
// this thread's number in it) and do only a share of its loop: there the guard leaves the
// region to libgomp, which makes a team of one (max-active-levels 0).
struct Nested {
  Seen inner;
  std::atomic<long> inlined{0};
};
void outer_body(void* data) {
  auto& nested = *static_cast<Nested*>(data);
  const long before = SerialOpenMp::inline_regions();
  {
    SerialOpenMp guard;
    GOMP_parallel(body, &nested.inner, 4, 0);
  }
  nested.inlined += SerialOpenMp::inline_regions() - before;
}
TEST(SerialOpenMp, ARegionInsideAUsersRegionIsATeamOfOne) {
  Nested nested;
  GOMP_parallel(outer_body, &nested, 2, 0);
  EXPECT_EQ(nested.inner.calls, 2);  // once per outer thread
  EXPECT_EQ(nested.inner.team, 1);
  EXPECT_EQ(nested.inner.level, 2);
  EXPECT_EQ(nested.inlined, 0);
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
  const long before_regions = SerialOpenMp::inline_regions();
  const EigenInterval top = certified_largest_eigenvalue(A);
  EXPECT_GT(top.factorizations, 0);
  // CHOLMOD's regions ran as plain calls: its GOMP_parallel is core's.
  EXPECT_GT(SerialOpenMp::inline_regions(), before_regions);
  EXPECT_LE(top.lo, 4.0);
  EXPECT_EQ(SerialOpenMp::max_active_levels(), before);
}

}  // namespace
}  // namespace dampbound::detail
