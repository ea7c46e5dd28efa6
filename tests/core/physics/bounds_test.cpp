// The bounds (eqs. 5, 6) against hand-computed values, and each damping policy (SPEC 4).
#include "core/physics/detail/numbers.hpp"
#include "dampbound/physics/bounds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace dampbound {
namespace {


TEST(LowerBound, TwoSqrtMKappa) {
  EXPECT_DOUBLE_EQ(lower_bound(0.001, 0.001), 0.002);
  EXPECT_DOUBLE_EQ(lower_bound(0.005, 0.1), 2 * std::sqrt(0.0005));
  EXPECT_DOUBLE_EQ(lower_bound(4, 9), 12);
}

TEST(UpperBound, HandComputed) {
  // v m/dt = (0.02, 0, 0); + F = (0.019, 0, 0); / |v| = 0.019.
  EXPECT_NEAR(upper_bound(Vec3(1, 0, 0), Vec3(-0.001, 0, 0), 0.001, 0.05), 0.019, 1e-15);
  // v m/dt = (0, 0.2, 0); + F = (0.03, 0.19, 0); |.| = sqrt(0.037); / 2.
  EXPECT_NEAR(upper_bound(Vec3(0, 2, 0), Vec3(0.03, -0.01, 0), 0.01, 0.1),
              std::sqrt(0.037) / 2, 1e-15);
  // A force that cancels the momentum term: the bound is 0.
  EXPECT_NEAR(upper_bound(Vec3(1, 0, 0), Vec3(-0.02, 0, 0), 0.001, 0.05), 0.0, 1e-17);
}

TEST(UpperBound, InfiniteAtRest) {
  EXPECT_EQ(upper_bound(Vec3::Zero(), Vec3(1, 2, 3), 1, 0.1), kInf);
}

TEST(Policy, FixedKeepsGammaAndFlagsViolations) {
  auto c = effective_damping(DampingPolicy::fixed, 0.001, 0.002, 0.01, 1);
  EXPECT_EQ(c.gamma, 0.001);
  EXPECT_TRUE(c.violating);
  EXPECT_EQ(c.status, NodeStatus::violating);
  c = effective_damping(DampingPolicy::fixed, 0.003, 0.002, 0.01, 1);
  EXPECT_FALSE(c.violating);
  EXPECT_EQ(c.status, NodeStatus::within);
  c = effective_damping(DampingPolicy::fixed, 0.02, 0.002, 0.01, 1);
  EXPECT_TRUE(c.violating);
}

TEST(Policy, ClampIntoBounds) {
  auto c = effective_damping(DampingPolicy::clamp, 0.001, 0.002, 0.01, 1);
  EXPECT_EQ(c.gamma, 0.002);
  EXPECT_EQ(c.status, NodeStatus::clamped);
  EXPECT_FALSE(c.violating);
  c = effective_damping(DampingPolicy::clamp, 0.05, 0.002, 0.01, 1);
  EXPECT_EQ(c.gamma, 0.01);
  c = effective_damping(DampingPolicy::clamp, 0.005, 0.002, 0.01, 1);
  EXPECT_EQ(c.gamma, 0.005);
  EXPECT_EQ(c.status, NodeStatus::within);
  c = effective_damping(DampingPolicy::clamp, 0.001, 0.002, kInf, 1);  // at rest
  EXPECT_EQ(c.gamma, 0.002);
}

TEST(Policy, ClampEmptyIntervalUsesUpperAndCounts) {
  auto c = effective_damping(DampingPolicy::clamp, 0.005, 0.004, 0.003, 1);
  EXPECT_EQ(c.gamma, 0.003);
  EXPECT_TRUE(c.unstabilisable);
  EXPECT_TRUE(c.violating);  // 0.003 < lo: outside [lo, hi]
  EXPECT_EQ(c.status, NodeStatus::unstabilisable);
}

TEST(Policy, UpperIsFactorTimesBound) {
  EXPECT_DOUBLE_EQ(effective_damping(DampingPolicy::upper, 0.1, 0.002, 0.01, 1.0).gamma, 0.01);
  auto c = effective_damping(DampingPolicy::upper, 0.1, 0.002, 0.01, 1.05);
  EXPECT_DOUBLE_EQ(c.gamma, 0.0105);
  EXPECT_TRUE(c.violating);
  EXPECT_EQ(effective_damping(DampingPolicy::upper, 0.1, 0.002, kInf, 1.05).gamma, 0.0);
}

TEST(Policy, LowerIsLowerBound) {
  auto c = effective_damping(DampingPolicy::lower, 0.1, 0.002, 0.01, 1);
  EXPECT_EQ(c.gamma, 0.002);
  EXPECT_EQ(c.status, NodeStatus::clamped);
  c = effective_damping(DampingPolicy::lower, 0.1, 0.02, 0.01, 1);
  EXPECT_TRUE(c.unstabilisable);
}

}  // namespace
}  // namespace dampbound
