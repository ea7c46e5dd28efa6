// SPEC 7's closed forms (include/dampbound/physics/closed_forms.hpp).
#include "dampbound/physics/closed_forms.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dampbound {
namespace {

// SPEC 7 stated once: the predicate, the damping limit and the undamped dt limit agree.
TEST(Spec7Limits, PredicateAndLimitsAgree) {
  // lambda = 4, m = 1, dt = 0.5: gamma_max = 2/0.5 - 4 * 0.5/2 = 3; dt_max = 2/sqrt(4) = 1.
  EXPECT_EQ(spec7_gamma_max(4, 1, 0.5), 3.0);
  EXPECT_EQ(spec7_gamma_max(4, 2, 0.5), 6.0);  // scales with m
  EXPECT_EQ(spec7_dt_max_undamped(4), 1.0);
  EXPECT_TRUE(std::isinf(spec7_dt_max_undamped(0)));
  EXPECT_FALSE(spec7_unstable(4, 2.9, 0.5));
  EXPECT_TRUE(spec7_unstable(4, 3.0, 0.5));
  EXPECT_TRUE(spec7_unstable(0, 4.0, 0.5));   // c dt = 2
  EXPECT_FALSE(spec7_unstable(4, 0, 0.999));  // undamped, below dt_max
  EXPECT_TRUE(spec7_unstable(4, 0, 1.0));
  const LinearLimits l = linear_limits(4, 1, 0.5);
  EXPECT_EQ(l.gamma_max, spec7_gamma_max(4, 1, 0.5));
  EXPECT_EQ(l.dt_max_undamped, spec7_dt_max_undamped(4));
}

TEST(Spec7Limits, SemiImplicitDtMaxIsTheRootOfTheIndex) {
  // lambda dt^2 + 2 c dt = 4 at the returned dt; 2/c without stiffness; 2/sqrt(lambda) undamped.
  for (double lambda : {0.5, 4.0, 1e4})
    for (double c : {0.0, 0.3, 7.0}) {
      const double dt = semi_implicit_dt_max(lambda, c);
      EXPECT_NEAR(lambda * dt * dt + 2 * c * dt, 4.0, 1e-12) << lambda << " " << c;
    }
  EXPECT_EQ(semi_implicit_dt_max(0, 4), 0.5);
  EXPECT_TRUE(std::isinf(semi_implicit_dt_max(0, 0)));
  EXPECT_DOUBLE_EQ(semi_implicit_dt_max(4, 0), spec7_dt_max_undamped(4));
}

}  // namespace
}  // namespace dampbound
