// Tests of core/analysis/detail/exact_over_budget: exact_stability's route over the
// factorisation budget factorises nothing, reports every exact number as NaN with the budget
// kept, and everything it proves without a factorisation holds: the bracket of lambda_max
// against Eigen's dense solver, and each proof of stability or instability, limit and
// threshold against the factorised route's exact numbers, for the paper's step (the index)
// and the per-mode integrators, at rest (K >= 0) and shaken.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/exact_over_budget.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "dampbound/run/scene.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

ExactOptions tight() {
  ExactOptions o;
  o.max_factor_flops = 1;
  return o;
}

double dense_top(const Model& m, const std::vector<Vec3>& x) {
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, x));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(A), Eigen::EigenvaluesOnly);
  return es.eigenvalues()(A.rows() - 1);
}

struct Case {
  Model model;
  std::vector<Vec3> x;
};

Case plane(const Params& p, bool shaken) {
  Case c{compile_model(make_grid(GridSpec{14, 14, 0.57, true, true}), p), {}};
  c.x = c.model.spec().rest;
  if (shaken) test::shake(c.x, 0.15, 5);
  return c;
}

TEST(ExactOverBudget, NothingIsFactorisedEveryExactNumberIsNaNAndTheBudgetIsKept) {
  Params p;
  const Case c = plane(p, false);
  const ExactStability e = exact_stability(c.model, c.x, p, tight());
  EXPECT_EQ(e.method, ExactMethod::over_budget);
  EXPECT_FALSE(e.computed());
  for (const double v : {e.spectrum.lambda_max, e.spectrum.lambda_min, e.lambda_max_lo,
                         e.spectral_radius, e.gamma_lo, e.gamma_hi, e.dt_max, e.index})
    EXPECT_TRUE(std::isnan(v));
  EXPECT_EQ(e.factor_budget, 1);
  EXPECT_GT(e.factor_flops, 1);
  EXPECT_GT(e.factor_bytes, 0);
  EXPECT_FALSE(e.not_computed_reason.empty());
  EXPECT_EQ(e.over_budget_reason(), e.not_computed_reason);
  // No unfactored steps: nothing tried, nothing proved.
  ExactOptions none = tight();
  none.unfactored_steps = 0;
  const ExactStability n = exact_stability(c.model, c.x, p, none);
  EXPECT_TRUE(std::isnan(n.unfactored.lambda_max_lo));
  EXPECT_TRUE(std::isnan(n.unfactored.index_at_least));
  EXPECT_FALSE(n.stable);
}

/// Each proof over the budget against the factorised route (and the dense top).
void expect_sound(const Case& c, double top, const Params& p, const std::string& what) {
  SCOPED_TRACE(what);
  const ExactStability e = exact_stability(c.model, c.x, p, tight());
  const ExactStability exact = exact_stability(c.model, c.x, p);
  ASSERT_TRUE(exact.computed());
  const ExactStability::Unfactored& b = e.unfactored;
  const double tol = 1e-9 * top;
  EXPECT_LE(b.lambda_max_lo, top + tol);
  EXPECT_GE(b.lambda_max_hi, top - tol);
  EXPECT_LE(b.lambda_max_hi, b.gershgorin);
  EXPECT_GT(b.lanczos_steps, 0);
  if (e.stable) {
    EXPECT_TRUE(exact.stable);
  }
  if (!std::isnan(b.dt_stable_up_to)) {
    EXPECT_LE(b.dt_stable_up_to, exact.dt_max * (1 + 1e-9));
  }
  if (b.gamma_stable_lo <= b.gamma_stable_hi) {
    EXPECT_GE(b.gamma_stable_lo, exact.gamma_lo * (1 - 1e-9));
    EXPECT_LE(b.gamma_stable_hi, exact.gamma_hi * (1 + 1e-9));
  }
  if (p.integrator == Integrator::semi_implicit_euler) {
    // The index lambda_max(dt^2 A + 2 dt C), C = gamma_i/m_i I at uniform rates.
    ASSERT_TRUE(exact.uniform_rate);
    const double index = p.dt * p.dt * top + 2 * p.dt * exact.rate_max;
    EXPECT_LE(b.index_at_least, index * (1 + 1e-9));
    if (!std::isnan(b.index_at_most)) {
      EXPECT_GE(b.index_at_most, index * (1 - 1e-9));
    }
    if (b.index_at_least >= 4) {
      EXPECT_FALSE(exact.stable);
    }
    EXPECT_GE(b.gamma_unstable_from, exact.gamma_hi * (1 - 1e-9));
    EXPECT_GE(b.dt_unstable_from, exact.dt_max * (1 - 1e-9));
  } else {
    ASSERT_FALSE(std::isnan(b.mode_unstable_from));
    if (b.lambda_max_lo >= b.mode_unstable_from) {
      EXPECT_FALSE(exact.stable);
    }
    if (!std::isnan(b.stable_lambda_hi)) {
      EXPECT_GE(b.stable_lambda_hi, top);
    }
    if (p.integrator == Integrator::rk4) {
      EXPECT_TRUE(std::isnan(b.dt_unstable_from));
      EXPECT_TRUE(std::isnan(b.gamma_unstable_below));
    } else {
      EXPECT_GE(b.dt_unstable_from, exact.dt_max * (1 - 1e-9));
      // Every gamma up to the threshold is unstable: none of them in a nonempty exact interval.
      if (std::isfinite(b.gamma_unstable_below) && exact.gamma_lo < exact.gamma_hi) {
        EXPECT_LE(b.gamma_unstable_below, exact.gamma_lo * (1 + 1e-9));
      }
    }
  }
}

TEST(ExactOverBudget, EveryProofHoldsAgainstTheFactorisedRoute) {
  for (const bool shaken : {false, true}) {
    Params p;
    p.gamma = 0.05;
    const Case c = plane(p, shaken);
    const double top = dense_top(c.model, c.x);
    for (const Integrator integ : {Integrator::semi_implicit_euler, Integrator::forward_euler,
                                   Integrator::verlet, Integrator::rk4}) {
      p.integrator = integ;
      p.dt = 0.05;
      const double dt_max = exact_stability(c.model, c.x, p).dt_max;
      for (const double f : {0.5, 1.01, 2.0}) {
        p.dt = std::isfinite(dt_max) && dt_max > 0 ? f * dt_max : 0.05 * f;
        expect_sound(c, top, p,
                     std::string(to_string(integ)) + (shaken ? " shaken" : " rest") + " dt " +
                         std::to_string(f) + " dt_max");
      }
    }
  }
}

TEST(ExactOverBudget, AtRestThePaperStepIsProvedEitherWayAwayFromItsLimit) {
  Params p;
  const Case c = plane(p, false);
  const double dt_max = exact_stability(c.model, c.x, p).dt_max;
  p.dt = 0.5 * dt_max;
  const ExactStability below = exact_stability(c.model, c.x, p, tight());
  EXPECT_TRUE(below.stable);
  EXPECT_LT(below.unfactored.index_at_most, 4);
  EXPECT_GE(below.unfactored.dt_stable_up_to, p.dt);
  p.dt = 1.5 * dt_max;
  const ExactStability above = exact_stability(c.model, c.x, p, tight());
  EXPECT_FALSE(above.stable);
  EXPECT_GE(above.unfactored.index_at_least, 4);
  EXPECT_LE(above.unfactored.dt_unstable_from, p.dt);
}

TEST(ExactOverBudget, PerModeIntegratorsAreProvedEitherWayAwayFromTheirLimit) {
  for (const Integrator integ : {Integrator::verlet, Integrator::rk4}) {
    Params p;
    p.integrator = integ;
    const Case c = plane(p, false);
    const double dt_max = exact_stability(c.model, c.x, p).dt_max;
    p.dt = 0.5 * dt_max;
    const ExactStability below = exact_stability(c.model, c.x, p, tight());
    EXPECT_TRUE(below.stable) << to_string(integ);
    EXPECT_GE(below.unfactored.dt_stable_up_to, p.dt) << to_string(integ);
    p.dt = 2 * dt_max;
    const ExactStability above = exact_stability(c.model, c.x, p, tight());
    EXPECT_FALSE(above.stable) << to_string(integ);
    EXPECT_GE(above.unfactored.lambda_max_lo, above.unfactored.mode_unstable_from)
        << to_string(integ);
  }
}

TEST(ExactOverBudget, RatesAreUniformWithin1e12OfTheLargest) {
  detail::ExactInputs in;
  in.r_min = in.r_max = 3;
  EXPECT_TRUE(detail::uniform_rates(in));
  in.r_min = 3 * (1 - 0.5e-12);
  EXPECT_TRUE(detail::uniform_rates(in));
  in.r_min = 3 * (1 - 2e-12);
  EXPECT_FALSE(detail::uniform_rates(in));
  in.r_min = in.r_max = 0;  // no damping anywhere
  EXPECT_TRUE(detail::uniform_rates(in));
}

TEST(ExactOverBudget, ImplicitEulerWithKPositiveSemidefiniteIsUnconditional) {
  Params p;
  p.integrator = Integrator::implicit_euler;
  p.dt = 10;
  const Case c = plane(p, false);
  const ExactStability e = exact_stability(c.model, c.x, p, tight());
  EXPECT_TRUE(e.unfactored.unconditional);
  EXPECT_TRUE(e.stable);
}

}  // namespace
}  // namespace dampbound
