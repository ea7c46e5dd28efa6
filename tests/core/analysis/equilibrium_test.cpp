// Tests of core/analysis/equilibrium: the net force, and the static equilibrium against where
// a damped run of step() settles, on a slack chain pulled down (K singular at rest), a
// pre-stretched and loaded random mesh, and a model already in equilibrium.
#include "core/analysis/equilibrium.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "dampbound/physics/step.hpp"
#include "tests/test_scenes.hpp"

namespace dampbound {
namespace {

/// Where a run of the paper's step from rest ends after `steps` steps, damped critically for
/// the slowest mode at `x` (gamma = 2 m sqrt(lambda_min), uniform masses): the fastest decay.
std::vector<Vec3> settled(const ModelSpec& spec, Params p, const std::vector<Vec3>& x,
                          int steps) {
  const Model at = compile_model(spec, p);
  p.gamma = 2 * p.m * std::sqrt(exact_stability(at, x, p).decaying.lambda_min);
  p.policy = DampingPolicy::fixed;
  const Model model = compile_model(spec, p);
  State state = rest_state(model);
  StepWorkspace ws;
  for (int k = 0; k < steps; ++k) step(model, p, state, ws);
  return state.x;
}

double largest_gap(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double d = 0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

TEST(Equilibrium, ASlackChainPulledDownSettlesWhereADampedRunDoes) {
  Params p;  // m = kappa = 0.001
  const Model m = compile_model(test::loaded_chain(0.0005), p);
  const NetForce at_rest = net_force(m, m.spec().rest);
  EXPECT_DOUBLE_EQ(at_rest.largest, 0.0005);  // the load itself: no spring is stretched
  EXPECT_FALSE(at_rest.balanced());
  const Equilibrium e = static_equilibrium(m);
  ASSERT_TRUE(e.converged) << e.net.largest;
  EXPECT_LE(e.net.largest, 1e-10 * e.net.scale);
  EXPECT_GT(e.iterations, 1);
  EXPECT_LT(e.x[6].y(), -0.1);  // it sags
  EXPECT_EQ(e.x[0], m.spec().rest[0]);  // fixed ends stay
  EXPECT_EQ(e.x[11], m.spec().rest[11]);
  EXPECT_LT(largest_gap(e.x, settled(test::loaded_chain(0.0005), p, e.x, 20000)), 1e-9);
}

TEST(Equilibrium, AMeshAlreadyInEquilibriumStaysAtRest) {
  ModelSpec s = test::loaded_chain(0);
  const Model m = compile_model(s, Params{});
  const Equilibrium e = static_equilibrium(m);
  EXPECT_TRUE(e.converged);
  EXPECT_EQ(e.iterations, 0);
  EXPECT_EQ(e.x, m.spec().rest);
  EXPECT_TRUE(net_force(m, m.spec().rest).balanced());
}

TEST(Equilibrium, APreStretchedLoadedMembraneSettlesWhereADampedRunDoes) {
  // A 14 x 14 membrane (432 free rows: CHOLMOD's route) with its edge fixed, every spring
  // shortened to 0.9 of its length (tension), pressed out of its plane with a load that varies
  // across it, and anchored.
  const int n = 14;
  ModelSpec s;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) add_node(s, Vec3(0.5 * a, 0, 0.5 * b));
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = n * a + b;
      if (b + 1 < n) add_spring(s, i, i + 1);
      if (a + 1 < n) add_spring(s, i, i + n);
      if (a + 1 < n && b + 1 < n) add_spring(s, i, i + n + 1);
      s.fixed[static_cast<size_t>(i)] = a == 0 || b == 0 || a == n - 1 || b == n - 1;
    }
  for (Spring& sp : s.springs) sp.rest_length *= 0.9;
  for (size_t i = 0; i < s.rest.size(); ++i) {
    const double k = static_cast<double>(i);
    s.anchor_scale[i] = 0.05;
    s.external_force[i] = Vec3(0.00002 * std::sin(0.7 * k), -0.0003 * (1 + 0.5 * std::cos(1.3 * k)), 0);
  }
  Params p;
  const Model m = compile_model(s, p);
  const Equilibrium e = static_equilibrium(m);
  ASSERT_TRUE(e.converged) << e.net.largest << " of " << e.net.scale << " after " << e.iterations;
  EXPECT_LE(e.iterations, 10);
  EXPECT_LT(largest_gap(e.x, settled(s, p, e.x, 20000)), 1e-9);
  // The analysis there differs from the one at rest: the load adds to the tension.
  EXPECT_NE(exact_stability(m, e.x, p).spectrum.lambda_max,
            exact_stability(m, m.spec().rest, p).spectrum.lambda_max);
  // Over a factorisation budget nothing is factorised.
  EquilibriumOptions tight;
  tight.max_factor_flops = 1;
  EXPECT_THROW(static_equilibrium(m, tight), FactorisationOverBudget);
}

}  // namespace
}  // namespace dampbound
