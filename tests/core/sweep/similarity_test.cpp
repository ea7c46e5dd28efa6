// SPEC 6 on the paper's mesh: trials of one similarity class (equal kappa/m, gamma/m, dt),
// each run separately through Session (the plain step()), agree.
//
// "Agree" means: the same outcome; iterations equal or one apart (members differ in
// rounding - 0.002/0.004 is not bit-for-bit the same trajectory as 0.001/0.002 - and a
// threshold crossed within rounding of a step boundary may be crossed one step later); the
// final maximum displacement equal to 1e-6 relative when the iterations are equal; counts of
// violating and unstabilisable node-steps equal to within 1 % (a node whose gamma sits within
// rounding of a bound may be counted on one side or the other).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "core/io/scene_file.hpp"
#include "core/sweep/grid.hpp"
#include "core/sweep/trials.hpp"

namespace dampbound {
namespace {

TEST(SweepSimilarity, EquivalentTrialsAgreeThroughSession) {
  SceneSpec scene = load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/paper-plane.toml");
  StopRules rules = scene.rules;
  rules.max_iterations = 150;
  SweepSpec s;
  s.m = parse_axis("--m", "0.001:0.006:0.001", AxisDomain::positive);
  s.kappa =
      parse_axis("--kappa", "0.001,0.002,0.003,0.004,0.006,0.008,0.6,0.9", AxisDomain::positive);
  s.gamma_mode = GammaMode::zeta;
  s.gamma = parse_axis("--zeta", "0.3,1", AxisDomain::non_negative);
  s.dt = parse_axis("--dt", "0.05", AxisDomain::positive);
  s.factor = parse_axis("--factor", "1", AxisDomain::non_negative);
  s.rules = rules;
  const SweepGrid grid(s);
  const TrialClasses classes = find_classes(grid, similarity_unavailable(scene));
  ASSERT_TRUE(classes.similarity) << classes.reason;
  std::map<std::uint32_t, std::vector<std::uint64_t>> members;
  for (std::uint64_t t = 0; t < grid.trials(); ++t) members[classes.class_of[t]].push_back(t);

  int compared = 0;
  std::map<Outcome, int> outcomes;
  for (const auto& [cls, trials] : members) {
    if (trials.size() < 2) continue;
    const TrialResult ref = run_reference(scene, s.policy, rules, grid.params(trials[0]));
    ++outcomes[ref.outcome];
    for (size_t k = 1; k < trials.size() && k < 3; ++k) {
      const TrialParams p = grid.params(trials[k]);
      SCOPED_TRACE("class " + std::to_string(cls) + ": m=" + std::to_string(p.m) +
                   " kappa=" + std::to_string(p.kappa) + " gamma=" + std::to_string(p.gamma));
      const TrialResult r = run_reference(scene, s.policy, rules, p);
      EXPECT_EQ(r.outcome, ref.outcome);
      EXPECT_LE(std::abs(r.iterations - ref.iterations), 1);
      if (r.iterations == ref.iterations && std::isfinite(ref.max_displacement)) {
        EXPECT_NEAR(r.max_displacement, ref.max_displacement, 1e-6 * ref.max_displacement);
      }
      const double tol_v = 0.01 * static_cast<double>(ref.violations) + 1;
      const double tol_u = 0.01 * static_cast<double>(ref.unstabilisable) + 1;
      EXPECT_NEAR(static_cast<double>(r.violations), static_cast<double>(ref.violations), tol_v);
      EXPECT_NEAR(static_cast<double>(r.unstabilisable), static_cast<double>(ref.unstabilisable),
                  tol_u);
      ++compared;
    }
  }
  EXPECT_GE(compared, 12);
  // The sample spans more than one outcome, so agreement is not trivial.
  EXPECT_GE(outcomes.size(), 2u);
}

}  // namespace
}  // namespace dampbound
