#include "core/analysis/detail/serial_openmp.hpp"

#include <gtest/gtest.h>

#include <thread>

#include "core/analysis/linear_stability_cholesky.hpp"

namespace dampbound::detail {
namespace {

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
