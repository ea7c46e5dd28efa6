// Sweep axes, decimals, trial enumeration and the exact similarity classes of SPEC 6.
#include "core/sweep/grid.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <set>
#include <string>

#include "core/io/scene_file.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {

SceneSpec grid_shipped(const std::string& name) {
  return load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/" + name + ".toml");
}

TEST(SweepDecimal, ParsesExactly) {
  EXPECT_EQ(parse_decimal("0.0003", "--m"), (Decimal{3, 4}));
  EXPECT_EQ(parse_decimal("3e-4", "--m"), (Decimal{3, 4}));
  EXPECT_EQ(parse_decimal("0.000300", "--m"), (Decimal{3, 4}));
  EXPECT_EQ(parse_decimal("12", "--m"), (Decimal{12, 0}));
  EXPECT_EQ(parse_decimal("1.2e1", "--m"), (Decimal{12, 0}));
  EXPECT_EQ(parse_decimal("0", "--m"), (Decimal{0, 0}));
  EXPECT_EQ(parse_decimal("1.05", "--m").text(), "1.05");
  EXPECT_EQ(parse_decimal("0.0001", "--m").text(), "0.0001");
  // The value is the double nearest the decimal, as if typed: 0.0003, not 3 * 0.0001.
  EXPECT_EQ(parse_decimal("0.0003", "--m").value(), 0.0003);
  for (const char* bad : {"", "abc", "1..2", "1e", "--1", "1,2", "nan", "inf", "0x10"})
    EXPECT_THROW(parse_decimal(bad, "--m"), InputError) << bad;
}

TEST(SweepAxis, RangesAndLists) {
  const Axis a = parse_axis("--m", "0.0001:0.001:0.0001", AxisDomain::positive);
  ASSERT_EQ(a.values.size(), 10u);
  EXPECT_EQ(a.values[2].text(), "0.0003");
  EXPECT_EQ(a.values.back().text(), "0.001");
  const Axis b = parse_axis("--zeta", "0.25,0.5,1", AxisDomain::non_negative);
  ASSERT_EQ(b.values.size(), 3u);
  EXPECT_EQ(b.values[1].text(), "0.5");
  // A step that does not divide the range stops at the last value <= B.
  EXPECT_EQ(parse_axis("--dt", "0.01:0.05:0.015", AxisDomain::positive).values.size(), 3u);
  EXPECT_EQ(parse_axis("--m", "1:1:1,2:3:0.5", AxisDomain::positive).values.size(), 4u);
}

TEST(SweepAxis, BadInputNamesTheFlag) {
  auto message = [](const std::string& spec, AxisDomain d) {
    try {
      parse_axis("--kappa", spec, d, 1000);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  for (const char* spec : {"0.1:0.01:0.01", "0.01:0.1:0", "0.01:0.1:-0.01", "0:1:0.1", "",
                           "0.1:0.2", "1:2:3:4", "0.001:10:0.001", "-1", "1,,2"}) {
    const std::string m = message(spec, AxisDomain::positive);
    EXPECT_EQ(m.rfind("--kappa: ", 0), 0u) << spec << " -> " << m;
  }
  EXPECT_NE(message("0.1:0.01:0.01", AxisDomain::positive).find("empty range"), std::string::npos);
  EXPECT_NE(message("0.01:0.1:0", AxisDomain::positive).find("step"), std::string::npos);
  EXPECT_EQ(message("0:1:0.5", AxisDomain::non_negative), "no error");
}

SweepSpec small_spec(const std::string& m, const std::string& kappa, GammaMode mode,
                     const std::string& gamma) {
  SweepSpec s;
  s.m = parse_axis("--m", m, AxisDomain::positive);
  s.kappa = parse_axis("--kappa", kappa, AxisDomain::positive);
  s.gamma_mode = mode;
  s.gamma =
      parse_axis(mode == GammaMode::zeta ? "--zeta" : "--gamma", gamma, AxisDomain::non_negative);
  s.dt = parse_axis("--dt", "0.05", AxisDomain::positive);
  s.factor = parse_axis("--factor", "1", AxisDomain::non_negative);
  return s;
}

TEST(SweepGrid, EnumeratesKappaFastest) {
  const SweepGrid g(small_spec("0.001:0.003:0.001", "0.01,0.02", GammaMode::zeta, "0.5,1"));
  ASSERT_EQ(g.trials(), 12u);
  const TrialParams p = g.params(7);  // gamma index 1, m index 0, kappa index 1
  EXPECT_EQ(p.m, 0.001);
  EXPECT_EQ(p.kappa, 0.02);
  EXPECT_EQ(p.gamma, 1.0 * lower_bound(0.001, 0.02));
  EXPECT_EQ(g.zeta(7), 1.0);
}

TEST(SweepClasses, ReducedFractionsOnTheIntegerGrid) {
  // m = a q, kappa = b q with q = 0.001, a, b = 1..12: classes are the distinct b/a per zeta.
  const SweepGrid g(
      small_spec("0.001:0.012:0.001", "0.001:0.012:0.001", GammaMode::zeta, "0.25,0.5"));
  const TrialClasses c = find_classes(g, similarity_unavailable(grid_shipped("paper-plane")));
  ASSERT_TRUE(c.similarity) << c.reason;
  std::set<std::pair<int, int>> fractions;
  for (int a = 1; a <= 12; ++a)
    for (int b = 1; b <= 12; ++b) fractions.insert({a / std::gcd(a, b), b / std::gcd(a, b)});
  EXPECT_EQ(c.count(), 2 * fractions.size());
  // Same class <=> same reduced fraction and zeta.
  for (std::uint64_t t = 0; t < g.trials(); ++t)
    for (std::uint64_t u = t + 1; u < g.trials(); u += 7) {
      const auto it = g.index(t), iu = g.index(u);
      const long at = static_cast<long>(it.m) + 1, bt = static_cast<long>(it.kappa) + 1;
      const long au = static_cast<long>(iu.m) + 1, bu = static_cast<long>(iu.kappa) + 1;
      const bool same = at * bu == au * bt && it.gamma == iu.gamma;
      EXPECT_EQ(c.class_of[t] == c.class_of[u], same) << t << " " << u;
    }
  // The representative is the first trial of its class.
  for (std::uint32_t k = 0; k < c.count(); ++k) {
    EXPECT_EQ(c.class_of[c.representative[k]], k);
    for (std::uint64_t t = 0; t < c.representative[k]; ++t) EXPECT_NE(c.class_of[t], k);
  }
}

TEST(SweepClasses, AbsoluteGammaUsesTheReducedTriple) {
  // (m, kappa, gamma) = (1, 2, 1) q and (2, 4, 2) q are one class; (2, 4, 1) q is not.
  const SweepGrid g(small_spec("0.001,0.002", "0.002,0.004", GammaMode::absolute, "0.001,0.002"));
  const TrialClasses c = find_classes(g, std::nullopt);
  ASSERT_TRUE(c.similarity);
  auto trial = [&](int gi, int mi, int ki) {
    return static_cast<std::uint64_t>((gi * 2 + mi) * 2 + ki);
  };
  EXPECT_EQ(c.class_of[trial(0, 0, 0)], c.class_of[trial(1, 1, 1)]);
  EXPECT_NE(c.class_of[trial(0, 0, 0)], c.class_of[trial(0, 1, 1)]);
  EXPECT_EQ(c.count(), 7u);  // 8 trials, one pair merged
}

TEST(SweepClasses, EveryPolicyThatReadsGammaKeepsItInTheKey) {
  // The reproducer: --m 0.001 --kappa 0.001 --gamma 0.0005,0.004,0.03 --policy safe put
  // the three trials in one class (the key held gamma for fixed and clamp only), and the sweep
  // reported all three settled where run --policy safe --gamma 0.03 does not settle.
  for (DampingPolicy policy : kPolicies) {
    SweepSpec spec = small_spec("0.001", "0.001", GammaMode::absolute, "0.0005,0.004,0.03");
    spec.policy = policy;
    const TrialClasses c = find_classes(SweepGrid(spec), std::nullopt);
    ASSERT_TRUE(c.similarity) << c.reason;
    EXPECT_EQ(c.count(), uses_user_gamma(policy) ? 3u : 1u) << to_string(policy);
  }
}

TEST(SweepClasses, FallsBackWhenTheSceneIsNotUniform) {
  SceneSpec s = grid_shipped("paper-plane");
  EXPECT_EQ(similarity_unavailable(s), std::nullopt);
  s.model.external_force[3] = Vec3(0, -1, 0);
  EXPECT_TRUE(similarity_unavailable(s));
  SceneSpec t = grid_shipped("paper-plane");
  t.model.mass_scale[10] = 2;
  EXPECT_TRUE(similarity_unavailable(t));
  const SweepGrid g(small_spec("0.001:0.004:0.001", "0.001:0.004:0.001", GammaMode::zeta, "1"));
  const TrialClasses c = find_classes(g, similarity_unavailable(t));
  EXPECT_FALSE(c.similarity);
  EXPECT_EQ(c.count(), g.trials());
  SweepSpec off = g.spec();
  off.allow_similarity = false;
  EXPECT_EQ(find_classes(SweepGrid(off), std::nullopt).count(), g.trials());
}

TEST(SweepClasses, UpperPolicyIgnoresGammaButKeepsFactor) {
  SweepSpec s = small_spec("0.001,0.002", "0.002,0.004", GammaMode::zeta, "0.5,1");
  s.factor = parse_axis("--factor", "1,1.05", AxisDomain::non_negative);
  s.policy = DampingPolicy::upper;
  const TrialClasses c = find_classes(SweepGrid(s), std::nullopt);
  // kappa/m in {2, 4, 1, 2} -> 3 ratios, times 2 factors; zeta does not matter.
  EXPECT_EQ(c.count(), 6u);
}

}  // namespace
}  // namespace dampbound
