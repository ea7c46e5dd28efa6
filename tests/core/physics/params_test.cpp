// The parameters: names of policies and integrators both ways, and validate()'s messages.
#include "dampbound/physics/params.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace dampbound {
namespace {

TEST(Params, DefaultsAreThePapersFigure1Setting) {
  const Params p = default_params();
  EXPECT_EQ(p.m, 0.001);
  EXPECT_EQ(p.kappa, 0.001);
  EXPECT_EQ(p.gamma, 0.002);  // 2 sqrt(m kappa)
  EXPECT_EQ(p.dt, 0.05);
  EXPECT_EQ(p.policy, DampingPolicy::fixed);
  EXPECT_EQ(p.integrator, Integrator::semi_implicit_euler);
  EXPECT_EQ(validate(p), std::nullopt);
}

TEST(Params, EveryPolicyAndIntegratorNameParsesBack) {
  for (auto x : kPolicies) EXPECT_EQ(parse_policy(to_string(x)), x) << to_string(x);
  for (auto x : kIntegrators) EXPECT_EQ(parse_integrator(to_string(x)), x) << to_string(x);
  EXPECT_EQ(policy_names(), (std::vector<std::string>{"fixed", "clamp", "upper", "lower", "safe"}));
  EXPECT_EQ(integrator_names().size(), 5u);
  EXPECT_EQ(integrator_names().front(), "semi-implicit-euler");
  EXPECT_STREQ(to_string(Integrator::semi_implicit_euler), "semi-implicit-euler");
  EXPECT_FALSE(parse_policy("Clamp"));
  EXPECT_FALSE(parse_policy(""));
  EXPECT_FALSE(parse_integrator("euler"));
}

TEST(Params, ValidateNamesTheFirstBadParameter) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto with = [](auto edit) {
    Params p;
    edit(p);
    return validate(p).value_or("usable");
  };
  EXPECT_EQ(with([](Params& p) { p.m = 0; }), "m must be > 0");
  EXPECT_EQ(with([&](Params& p) { p.kappa = inf; }), "kappa must be finite");
  EXPECT_EQ(with([&](Params& p) { p.gamma = nan; }), "gamma must be finite");
  EXPECT_EQ(with([](Params& p) { p.gamma = -1e-9; }), "gamma must be >= 0");
  EXPECT_EQ(with([](Params& p) { p.dt = -0.05; }), "dt must be > 0");
  EXPECT_EQ(with([](Params& p) { p.factor = -1; }), "factor must be >= 0");
  EXPECT_EQ(with([](Params& p) { p.gamma = 0, p.factor = 0; }), "usable");  // zero is allowed
}

}  // namespace
}  // namespace dampbound
