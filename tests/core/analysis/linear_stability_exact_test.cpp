// The exact linear stability (core/analysis/linear_stability_exact.hpp): on the two-node
// system every number has a closed form; a chain with unequal masses takes the symmetric
// index; the simulation check agrees with the limits.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/linear_stability_exact.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>

#include "core/analysis/linear_stability_modes.hpp"
#include "core/analysis/perturbation_growth.hpp"
#include "core/io/scene_file.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

/// A 14 x 14 plane whose masses vary 12x (as a tetrahedral mesh's lumped masses do), so
/// gamma/m_i varies and the paper's step takes the symmetric index.
ModelSpec plane_with_masses_12x_apart() {
  ModelSpec spec = make_grid(GridSpec{14, 14, 0.57, true, true});
  for (size_t i = 0; i < spec.mass_scale.size(); ++i)
    spec.mass_scale[i] = 1 + 11.0 * static_cast<double>(i % 5) / 4;
  return spec;
}

/// That plane at gamma 0.02 (policy fixed): its exact analysis, and one over a 1-flop budget.
struct PlaneOverBudget {
  Params p = [] {
    Params q;
    q.gamma = 0.02;
    q.policy = DampingPolicy::fixed;
    return q;
  }();
  Model model = compile_model(plane_with_masses_12x_apart(), p);
  ExactStability free = exact_stability(model, model.spec().rest, p);
  ExactOptions tight = [] {
    ExactOptions o;
    o.max_factor_flops = 1;
    return o;
  }();
  ExactStability over = exact_stability(model, model.spec().rest, p, tight);
};

/// Two exact analyses that should agree bit for bit: the method, both ends of the spectrum,
/// the limits, the radius and the verdict.
void expect_same_numbers(const ExactStability& a, const ExactStability& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.spectrum.lambda_max, b.spectrum.lambda_max);
  EXPECT_EQ(a.spectrum.lambda_min, b.spectrum.lambda_min);
  EXPECT_EQ(a.gamma_hi, b.gamma_hi);
  EXPECT_EQ(a.dt_max, b.dt_max);
  EXPECT_EQ(a.spectral_radius, b.spectral_radius) << to_string(a.integrator);
  EXPECT_EQ(a.stable, b.stable);
}

struct TwoNode {
  SceneSpec scene = load_scene(test::source_path("scenes/two-node.toml"));
  Params params = scene.params;  // m = kappa = 0.001, gamma = 0.002 (c = 2), dt = 0.05
  Model model = compile_model(scene.model, params);
};

TEST(LinearStabilityExact, TwoNodeClosedForms) {
  const TwoNode t;
  const ExactStability e = exact_stability(t.model, t.model.spec().rest, t.params);
  EXPECT_EQ(e.method, ExactMethod::per_mode);
  EXPECT_STREQ(to_string(e.method), "per-mode (uniform gamma/m)");
  EXPECT_TRUE(e.uniform_rate);
  EXPECT_DOUBLE_EQ(e.rate_min, 2.0);
  EXPECT_DOUBLE_EQ(e.rate_max, 2.0);
  // M^-1 K: kappa/m = 1 along the spring, 0 across it (two zero modes).
  EXPECT_NEAR(e.spectrum.lambda_max, 1.0, 1e-9);
  EXPECT_LE(e.lambda_max_lo, e.spectrum.lambda_max);
  EXPECT_NEAR(e.spectrum.lambda_min, 0.0, 1e-9);
  EXPECT_TRUE(e.zero_modes);
  EXPECT_NEAR(e.decaying.lambda_min, 1.0, 1e-9);
  // The x mode: z = 0.96 and 0.9375 (trace 1.8975, determinant 0.9).
  EXPECT_NEAR(e.spectral_radius, 0.96, 1e-9);
  EXPECT_TRUE(e.stable);
  // SPEC 7: c < (4 - lambda h^2)/(2 h) = 39.975 -> gamma < 0.039975; dt < 2 sqrt 2 - 2 at c = 2.
  EXPECT_EQ(e.gamma_lo, 0.0);
  EXPECT_NEAR(e.gamma_hi, 0.039975, 1e-12);
  EXPECT_NEAR(e.dt_max, 2 * std::sqrt(2.0) - 2, 1e-9);
}

TEST(LinearStabilityExact, TwoNodeOtherIntegratorsClosedForms) {
  // The zero modes (lambda = 0: z = 1 and the real root R(-c dt)) set the limits at c = 2:
  // forward Euler 1 - c dt >= -1 (dt <= 1; the x mode needs dt < c/lambda = 2), RK4 its real
  // interval's end 2.7852936/c, Verlet 2/sqrt(lambda_max) whatever the damping. Their radii at
  // tiny steps are 1 and 1 - c dt: computed as tr^2 - 4 det the difference's rounding put the
  // radius above 1 + 1e-12 and every dt_max here near 7e-7 s.
  struct Case {
    Integrator integrator;
    double dt_max;
  };
  for (const Case k : {Case{Integrator::forward_euler, 1.0}, Case{Integrator::verlet, 2.0},
                       Case{Integrator::rk4, 2.785293563405282 / 2}}) {
    TwoNode t;
    t.params.integrator = k.integrator;
    const ExactStability e = exact_stability(t.model, t.model.spec().rest, t.params);
    SCOPED_TRACE(to_string(k.integrator));
    EXPECT_EQ(e.method, ExactMethod::per_mode);
    EXPECT_TRUE(e.stable);
    EXPECT_NEAR(e.dt_max, k.dt_max, 1e-9 * k.dt_max);
    for (double h : {1e-9, 1e-7, 1e-5, 1e-3})
      EXPECT_LE(mode_spectral_radius(k.integrator, 0, 2, h), 1 + 1e-12) << h;
  }
}

TEST(LinearStabilityExact, EveryVerdictAgreesWithItsLimitsAndItsInnerEndsOnTheScenes) {
  // Per mode (uniform gamma/m) the verdict, the dt limit and the gamma interval come from one
  // spectrum: at the scene's dt and gamma they must agree, for every explicit integrator.
  // ExactStability::Inner, the same numbers over [lambda_min_hi, lambda_max_lo], lies on the
  // far side of them (a smaller spectrum is no less stable) and, where every certificate
  // holds, within 1e-8 of them.
  int checked = 0;
  const auto near = [](double a, double b) { return a == b || std::abs(a - b) <= 1e-8 * b; };
  for (const char* name : {"two-node", "two-node-damping", "paper-plane", "paper-plane-safe",
                           "paper-plane-stiff", "quad-cloth", "tissue-cap"}) {
    const SceneSpec scene = load_scene(test::source_path(std::string("scenes/") + name + ".toml"));
    for (Integrator i : {Integrator::semi_implicit_euler, Integrator::forward_euler,
                         Integrator::verlet, Integrator::rk4}) {
      Params p = scene.params;
      p.integrator = i;
      const Model model = compile_model(scene.model, p);
      const ExactStability e = exact_stability(model, model.spec().rest, p);
      SCOPED_TRACE(std::string(name) + " " + to_string(i));
      EXPECT_LE(e.spectrum.lambda_min, e.lambda_min_hi);
      EXPECT_NEAR(e.lambda_min_hi, e.spectrum.lambda_min, 1e-8 * e.spectrum.lambda_max);
      const ExactStability::Inner& in = e.inner;
      if (e.method != ExactMethod::per_mode) {
        EXPECT_TRUE(std::isnan(in.spectral_radius) && std::isnan(in.dt_max));
        continue;
      }
      EXPECT_EQ(e.stable, p.dt <= e.dt_max) << "dt_max " << e.dt_max;
      EXPECT_EQ(e.stable, e.gamma_lo <= p.gamma && p.gamma < e.gamma_hi)
          << "[" << e.gamma_lo << ", " << e.gamma_hi << ")";
      EXPECT_LE(in.spectral_radius, e.spectral_radius * (1 + 1e-12));
      EXPECT_TRUE(near(in.spectral_radius, e.spectral_radius)) << in.spectral_radius;
      // SPEC 7's (sqrt(c^2 + 4 lambda) - c)/lambda cancels where c^2 >> lambda: 3e-12 relative
      // on paper-plane-safe (c = 1000). SPEC 9's dt_safe shares it, and its ties between
      // nodes depend on those bits, so it stays as the SPEC writes it.
      EXPECT_GE(in.dt_max, e.dt_max * (1 - 1e-10));
      EXPECT_TRUE(near(in.dt_max, e.dt_max)) << in.dt_max << " " << e.dt_max;
      EXPECT_GE(in.gamma_hi, e.gamma_hi * (1 - 1e-12));
      EXPECT_TRUE(near(in.gamma_hi, e.gamma_hi)) << in.gamma_hi << " " << e.gamma_hi;
      EXPECT_LE(in.gamma_lo, e.gamma_lo * (1 + 1e-12));
      EXPECT_EQ(in.stable, e.stable);
      ++checked;
    }
  }
  EXPECT_GE(checked, 20);
}

TEST(LinearStabilityExact, ImplicitEulerIsUnconditional) {
  TwoNode t;
  t.params.integrator = Integrator::implicit_euler;
  const ExactStability e = exact_stability(t.model, t.model.spec().rest, t.params);
  EXPECT_EQ(e.method, ExactMethod::unconditional);
  EXPECT_TRUE(e.stable);
  EXPECT_TRUE(std::isinf(e.gamma_hi));
  EXPECT_TRUE(std::isinf(e.dt_max));
  EXPECT_LT(e.spectral_radius, 1.0);  // uniform rate: the per-mode radius
}

TEST(LinearStabilityExact, SpectralRadiusAtAnotherGamma) {
  const TwoNode t;
  const ExactStability e = exact_stability(t.model, t.model.spec().rest, t.params);
  const SparseMatrix A = mass_weighted(t.model, tangent_stiffness(t.model, t.model.spec().rest));
  // gamma = 0: c = 0, the undamped x mode has |z| = 1.
  EXPECT_NEAR(spectral_radius_at(t.model, A, e, t.params, 0.0).rho, 1.0, 1e-12);
  EXPECT_NEAR(spectral_radius_at(t.model, A, e, t.params, 0.002).rho, 0.96, 1e-9);
  EXPECT_GT(spectral_radius_at(t.model, A, e, t.params, 0.041).rho, 1.0);  // past gamma_hi
}

TEST(LinearStabilityExact, SimulationAgreesWithTheLimits) {
  TwoNode t;
  EXPECT_LT(perturbation_growth(t.model, t.params, 200), 1.0);
  t.params.dt = 1.0;  // > 2 sqrt 2 - 2: z = (-1 - sqrt 5)/2 per step
  EXPECT_GT(perturbation_growth(t.model, t.params, 20), 100.0);
  // Deterministic: the same seed, the same number.
  EXPECT_EQ(perturbation_growth(t.model, t.params, 5), perturbation_growth(t.model, t.params, 5));
}

TEST(LinearStabilityExact, UnequalMassesTakeTheSymmetricIndex) {
  // A chain fixed at one end: 0 (fixed) - 1 - 2, node 2 twice as heavy, so gamma/m differs.
  ModelSpec spec;
  for (int k = 0; k < 3; ++k) add_node(spec, Vec3(k, 0, 0));
  add_spring(spec, 0, 1);
  add_spring(spec, 1, 2);
  spec.fixed[0] = 1;
  spec.mass_scale[2] = 2;
  Params p;
  p.m = 0.001, p.kappa = 0.001, p.gamma = 0.002, p.dt = 0.05;
  p.policy = DampingPolicy::fixed;
  const Model m = compile_model(spec, p);
  const ExactStability e = exact_stability(m, m.spec().rest, p);
  EXPECT_EQ(e.method, ExactMethod::symmetric_index);
  EXPECT_FALSE(e.uniform_rate);
  EXPECT_DOUBLE_EQ(e.rate_min, 1.0);  // gamma / (2 m)
  EXPECT_DOUBLE_EQ(e.rate_max, 2.0);
  EXPECT_TRUE(e.stable);
  EXPECT_LT(e.index, 4.0);
  EXPECT_GT(e.dt_max, p.dt);
  EXPECT_GT(e.gamma_hi, p.gamma);
  // Inside the dt limit the perturbation decays, past it it grows.
  Params in = p, out = p;
  in.dt = 0.9 * e.dt_max;
  out.dt = 1.2 * e.dt_max;
  EXPECT_LT(perturbation_growth(m, in, 2000), 1.0);
  EXPECT_GT(perturbation_growth(m, out, 2000), 1.0);
}

TEST(LinearStabilityExact, WhetherNoDampingIsUnstableComesFromTheSpectrumAsFromTheIndex) {
  // The paper's step without damping is stable where dt^2 lambda_max < 4: the gamma search
  // reads that from A's certified lambda_max (no factorisation of its own) when the product
  // lies clear of 4, and computes lambda_max(dt^2 A) as before only near 4. Just past and just
  // inside the undamped limit, against the dense eigenvalues of A: past it no gamma is
  // stable, inside it some are.
  Params p;
  p.gamma = 0.02;
  p.policy = DampingPolicy::fixed;
  const Model model = compile_model(plane_with_masses_12x_apart(), p);  // 588 rows: factored
  const Eigen::MatrixXd dense =
      Eigen::MatrixXd(mass_weighted(model, tangent_stiffness(model, model.spec().rest)));
  const double lambda_max =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense).eigenvalues().maxCoeff();
  const double edge = 2 / std::sqrt(lambda_max);
  for (const double factor : {1 + 1e-3, 1 + 1e-6, 1 - 1e-6, 1 - 1e-3}) {
    Params q = p;
    q.dt = edge * factor;
    const ExactStability e = exact_stability(model, model.spec().rest, q);
    ASSERT_EQ(e.method, ExactMethod::symmetric_index);
    EXPECT_LE(e.lambda_max_lo, lambda_max * (1 + 1e-12));
    EXPECT_GE(e.spectrum.lambda_max, lambda_max * (1 - 1e-12));
    if (factor > 1) {
      EXPECT_EQ(e.gamma_hi, 0.0) << factor;
      EXPECT_FALSE(e.stable) << factor;
    } else {
      EXPECT_GT(e.gamma_hi, 0.0) << factor;
    }
  }
}

TEST(LinearStabilityExact, NewtonsLimitsAreTheIndexRootsToNineDigits) {
  // gamma_hi and dt_max of the plane whose masses vary 12x, against the dense index
  // lambda_max(dt^2 A + 2 dt gamma diag(R)): below 4 just inside each limit (1e-9 relative),
  // above it just outside. Newton stops when its next step would be below 1e-13 of the root
  // (the certified lambda_max lies up to 1e-10 above, which moves the roots that much).
  Params p;
  p.gamma = 0.02;
  p.policy = DampingPolicy::fixed;
  const Model model = compile_model(plane_with_masses_12x_apart(), p);
  const ExactStability e = exact_stability(model, model.spec().rest, p);
  ASSERT_EQ(e.method, ExactMethod::symmetric_index);
  const Eigen::MatrixXd A =
      Eigen::MatrixXd(mass_weighted(model, tangent_stiffness(model, model.spec().rest)));
  const Eigen::VectorXd R = damping_rates(model, model.spec().gamma_scale);
  const auto index = [&](double gamma, double h) {
    Eigen::MatrixXd S = h * h * A;
    S.diagonal() += 2 * h * gamma * R;
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly)
        .eigenvalues()
        .maxCoeff();
  };
  ASSERT_GT(e.gamma_hi, p.gamma);
  ASSERT_GT(e.dt_max, p.dt);
  EXPECT_LT(index(e.gamma_hi * (1 - 1e-9), p.dt), 4);
  EXPECT_GT(index(e.gamma_hi * (1 + 1e-9), p.dt), 4);
  EXPECT_LT(index(p.gamma, e.dt_max * (1 - 1e-9)), 4);
  EXPECT_GT(index(p.gamma, e.dt_max * (1 + 1e-9)), 4);
}

TEST(LinearStabilityExact, TheRadiusBesideTheFactorisationsGivesTheBitsOfOneThread) {
  // On two or more threads the spectral radius at non-uniform rates runs beside the
  // factorisations: the symmetric index's (semi-implicit Euler) or the spectrum's (forward
  // Euler, Verlet, RK4). Every number as on one thread.
  for (const Integrator integrator : {Integrator::semi_implicit_euler, Integrator::forward_euler,
                                      Integrator::verlet, Integrator::rk4}) {
    Params p;
    p.gamma = 0.02;
    p.policy = DampingPolicy::fixed;
    p.integrator = integrator;
    const Model model = compile_model(plane_with_masses_12x_apart(), p);
    ExactOptions one, two;
    one.threads = 1;
    two.threads = 2;
    const ExactStability a = exact_stability(model, model.spec().rest, p, one);
    const ExactStability b = exact_stability(model, model.spec().rest, p, two);
    ASSERT_FALSE(a.uniform_rate);
    ASSERT_FALSE(std::isnan(a.spectral_radius)) << to_string(integrator);
    expect_same_numbers(a, b);
    EXPECT_EQ(a.radius_converged, b.radius_converged);
    if (integrator == Integrator::semi_implicit_euler) {
      EXPECT_EQ(a.index, b.index);
    }
  }
}

TEST(LinearStabilityExact, OverTheFactorisationBudgetNothingIsComputed) {
  Params p;
  const Model model = compile_model(make_grid(GridSpec{14, 14, 0.57, true, true}), p);  // 588 rows
  const ExactStability free = exact_stability(model, model.spec().rest, p);
  ASSERT_TRUE(free.computed());
  ExactOptions tight;
  tight.max_factor_flops = 1;
  const ExactStability over = exact_stability(model, model.spec().rest, p, tight);
  EXPECT_FALSE(over.computed());
  EXPECT_EQ(over.method, ExactMethod::over_budget);
  EXPECT_STREQ(to_string(over.method), "not computed (factorisation over budget)");
  // Not computed, but proved: Gershgorin on the index matrix (SPEC 9's safe bound) at rest.
  EXPECT_TRUE(over.stable);
  for (double v : {over.spectrum.lambda_max, over.spectrum.lambda_min, over.lambda_max_lo,
                   over.gamma_lo, over.gamma_hi, over.dt_max, over.spectral_radius})
    EXPECT_TRUE(std::isnan(v));
  EXPECT_GT(over.factor_flops, 1.0);
  EXPECT_EQ(over.factor_budget, 1.0);
  EXPECT_NE(over.over_budget_reason().find("GFlop"), std::string::npos) << over.over_budget_reason();
  // A budget above the prediction changes nothing.
  ExactOptions roomy;
  roomy.max_factor_flops = 2 * over.factor_flops;
  expect_same_numbers(exact_stability(model, model.spec().rest, p, roomy), free);
}

TEST(LinearStabilityExact, OverTheBudgetLanczosProvesInstabilityWithoutAFactorisation) {
  // A plane whose masses vary 12x (as a tetrahedral mesh's lumped masses do), so gamma/m_i
  // varies and the paper's step takes the symmetric index.
  const PlaneOverBudget t;
  const Params& p = t.p;
  const Model& model = t.model;
  const ExactStability& free = t.free;
  ExactOptions tight = t.tight;
  const ExactStability& over = t.over;
  ASSERT_EQ(free.method, ExactMethod::symmetric_index);
  ASSERT_FALSE(over.computed());
  const ExactStability::Unfactored& b = over.unfactored;
  EXPECT_GT(b.lanczos_steps, 0);
  EXPECT_LE(b.lanczos_steps, tight.unfactored_steps);
  // Every bound on the proved side of the exact (certified) numbers ...
  EXPECT_LE(b.lambda_max_lo, free.lambda_max_lo);
  EXPECT_GE(b.lambda_max_hi, free.spectrum.lambda_max);
  EXPECT_LE(b.index_at_least, free.index);
  EXPECT_GE(b.gamma_unstable_from, free.gamma_hi);
  EXPECT_GE(b.dt_unstable_from, free.dt_max);
  // ... and close to them: the vector is aimed at the index matrix at the scene's gamma, dt.
  EXPECT_GT(b.index_at_least, free.index * (1 - 1e-5));
  EXPECT_LT(b.gamma_unstable_from, free.gamma_hi * (1 + 1e-4));
  EXPECT_LT(b.dt_unstable_from, free.dt_max * (1 + 1e-4));
  // No steps: nothing tried.
  tight.unfactored_steps = 0;
  const ExactStability bare = exact_stability(model, model.spec().rest, p, tight);
  for (double v : {bare.unfactored.lambda_max_lo, bare.unfactored.index_at_least,
                   bare.unfactored.gamma_unstable_from, bare.unfactored.dt_unstable_from})
    EXPECT_TRUE(std::isnan(v));
}

TEST(LinearStabilityExact, OverTheBudgetGershgorinProvesThePaperStepStable) {
  // The plane whose masses vary 12x: Gershgorin on the index matrix's rows is SPEC 9's safe
  // bound, node by node, so the stable side over the budget is the safe bound's numbers, and
  // lies inside the exact limits.
  const PlaneOverBudget t;
  const Params& p = t.p;
  const Model& model = t.model;
  const ExactStability& free = t.free;
  const ExactOptions& tight = t.tight;
  const ExactStability& over = t.over;
  ASSERT_EQ(free.method, ExactMethod::symmetric_index);
  const ExactStability::Unfactored& b = over.unfactored;
  const SafeBoundSummary safe = safe_bound_summary(model, model.spec().rest, p.dt);
  ASSERT_EQ(safe.gamma_over, 0);  // every node within its safe bound at gamma 0.02
  EXPECT_TRUE(over.stable);
  EXPECT_LT(b.index_at_most, 4);
  EXPECT_GE(b.index_at_most, free.index);
  EXPECT_EQ(b.gamma_stable_lo, 0);
  EXPECT_LE(b.gamma_stable_hi, free.gamma_hi);
  EXPECT_NEAR(b.gamma_stable_hi, safe.gamma_safe, 1e-10 * safe.gamma_safe);
  EXPECT_LE(b.gamma_stable_hi, safe.gamma_safe);
  EXPECT_LE(b.dt_stable_up_to, free.dt_max);
  EXPECT_NEAR(b.dt_stable_up_to, safe.dt_safe, 1e-10 * safe.dt_safe);
  EXPECT_LE(b.dt_stable_up_to, safe.dt_safe);
  EXPECT_TRUE(std::isnan(b.stable_lambda_hi));  // the per-mode field: other integrators'
  // Past the safe bound but short of the exact limit: neither side is proved.
  Params between = p;
  between.gamma = 0.5 * (safe.gamma_safe + free.gamma_hi);
  const Model mb = compile_model(plane_with_masses_12x_apart(), between);
  const ExactStability open = exact_stability(mb, mb.spec().rest, between, tight);
  EXPECT_FALSE(open.stable);
  EXPECT_GE(open.unfactored.index_at_most, 4);
  EXPECT_LT(open.unfactored.index_at_least, 4);
  EXPECT_NEAR(open.unfactored.gamma_stable_hi, b.gamma_stable_hi, 1e-15);  // gamma-free
  // Squeezed to 90 %, every spring is compressed: nothing proves K >= 0, nor stability.
  std::vector<Vec3> squeezed = model.spec().rest;
  for (Vec3& x : squeezed) x *= 0.9;
  const ExactStability sq = exact_stability(model, squeezed, p, tight);
  EXPECT_FALSE(sq.stable);
  for (double v :
       {sq.unfactored.index_at_most, sq.unfactored.gamma_stable_hi, sq.unfactored.dt_stable_up_to})
    EXPECT_TRUE(std::isnan(v));
}

TEST(LinearStabilityExact, OverTheBudgetImplicitEulerIsUnconditionalWhenNoSpringIsCompressed) {
  Params p;
  p.integrator = Integrator::implicit_euler;
  const Model model = compile_model(make_grid(GridSpec{14, 14, 0.57, true, true}), p);
  ExactOptions tight;
  tight.max_factor_flops = 1;
  // At rest every spring block is positive semidefinite: stable for every dt and gamma, as the
  // computed route says, with no factorisation.
  const ExactStability free = exact_stability(model, model.spec().rest, p);
  ASSERT_EQ(free.method, ExactMethod::unconditional);
  const ExactStability over = exact_stability(model, model.spec().rest, p, tight);
  EXPECT_FALSE(over.computed());
  EXPECT_TRUE(over.unfactored.unconditional);
  EXPECT_TRUE(over.stable);
  // Squeezed to 90 %, every spring is compressed: nothing proves K >= 0 without a factorisation.
  std::vector<Vec3> squeezed = model.spec().rest;
  for (Vec3& x : squeezed) x *= 0.9;
  const ExactStability tight_squeeze = exact_stability(model, squeezed, p, tight);
  EXPECT_FALSE(tight_squeeze.unfactored.unconditional);
  EXPECT_FALSE(tight_squeeze.stable);
  // The paper's step is never unconditional.
  p.integrator = Integrator::semi_implicit_euler;
  EXPECT_FALSE(exact_stability(model, model.spec().rest, p, tight).unfactored.unconditional);
}

TEST(LinearStabilityExact, OverTheBudgetUniformRatesGiveThePerModeLimitsFromBelow) {
  // A plane with one mass (uniform gamma/m): the thresholds are SPEC 7's per-mode limits at
  // lambda = the Rayleigh quotient, 2m/dt - m lo dt/2 and dt at the root.
  Params p;
  p.gamma = 0.001;
  const Model model = compile_model(make_grid(GridSpec{14, 14, 0.57, true, true}), p);
  const ExactStability free = exact_stability(model, model.spec().rest, p);
  ASSERT_EQ(free.method, ExactMethod::per_mode);
  ExactOptions tight;
  tight.max_factor_flops = 1;
  const ExactStability over = exact_stability(model, model.spec().rest, p, tight);
  const ExactStability::Unfactored& b = over.unfactored;
  EXPECT_GE(b.gamma_unstable_from, free.gamma_hi);
  EXPECT_GE(b.dt_unstable_from, free.dt_max);
  EXPECT_LT(b.gamma_unstable_from, free.gamma_hi * (1 + 1e-3));
  EXPECT_LT(b.dt_unstable_from, free.dt_max * (1 + 1e-3));
  const double lo = b.lambda_max_lo;
  EXPECT_NEAR(b.gamma_unstable_from, 2 * p.m / p.dt - p.m * lo * p.dt / 2, 1e-12 * p.m / p.dt);
  // Forward Euler and Verlet: mode_instability at lambda = the Rayleigh quotient, on the
  // unstable side of the computed per-mode limits and close to them.
  for (Integrator i : {Integrator::forward_euler, Integrator::verlet}) {
    p.integrator = i;
    const ExactStability exact = exact_stability(model, model.spec().rest, p);
    ASSERT_EQ(exact.method, ExactMethod::per_mode);
    const ExactStability::Unfactored& u = exact_stability(model, model.spec().rest, p, tight).unfactored;
    SCOPED_TRACE(to_string(i));
    EXPECT_GE(u.dt_unstable_from, exact.dt_max);
    EXPECT_LT(u.dt_unstable_from, exact.dt_max * (1 + 1e-3));
    EXPECT_GE(u.mode_unstable_from, exact.spectrum.lambda_max);  // the user's dt is stable
    EXPECT_TRUE(std::isnan(u.index_at_least));
    // The stable side: inside the computed limits, and the scene's parameters proved stable.
    EXPECT_LE(u.dt_stable_up_to, exact.dt_max);
    EXPECT_GT(u.dt_stable_up_to, 0.5 * exact.dt_max);
    EXPECT_GE(u.gamma_stable_lo, exact.gamma_lo);
    EXPECT_LE(u.gamma_stable_hi, exact.gamma_hi);
    EXPECT_GE(u.stable_lambda_hi, exact.spectrum.lambda_max);
    EXPECT_TRUE(exact_stability(model, model.spec().rest, p, tight).stable);
    // Squeezed to 90 %, every spring is compressed: nothing proves K >= 0, nor stability.
    std::vector<Vec3> squeezed = model.spec().rest;
    for (Vec3& x : squeezed) x *= 0.9;
    const ExactStability sq = exact_stability(model, squeezed, p, tight);
    EXPECT_TRUE(std::isnan(sq.unfactored.dt_stable_up_to));
    EXPECT_FALSE(sq.stable);
    if (i == Integrator::forward_euler) {  // too little damping: gamma below gamma_lo
      EXPECT_LE(u.gamma_unstable_below, exact.gamma_lo);
      EXPECT_GT(u.gamma_unstable_below, exact.gamma_lo * (1 - 1e-3));
    } else {
      EXPECT_EQ(u.gamma_unstable_below, -std::numeric_limits<double>::infinity());  // at this dt no gamma is proved unstable
    }
  }
  // RK4: a certified lambda from which every mode is unstable at the user's gamma and dt,
  // no thresholds. At the scene's dt the step is not proved unstable; 1 % past the computed
  // dt limit it is.
  p.integrator = Integrator::rk4;
  const ExactStability rk4_free = exact_stability(model, model.spec().rest, p);
  const ExactStability rk4 = exact_stability(model, model.spec().rest, p, tight);
  EXPECT_LE(rk4.unfactored.lambda_max_lo, free.spectrum.lambda_max);
  EXPECT_TRUE(std::isnan(rk4.unfactored.dt_unstable_from));
  EXPECT_TRUE(std::isnan(rk4.unfactored.gamma_unstable_below));
  EXPECT_GT(rk4.unfactored.mode_unstable_from, rk4_free.spectrum.lambda_max);
  p.dt = 1.01 * rk4_free.dt_max;
  const ExactStability past = exact_stability(model, model.spec().rest, p, tight);
  EXPECT_GE(past.unfactored.lambda_max_lo, past.unfactored.mode_unstable_from);
  // Rates that differ between nodes: no per-mode proof.
  ModelSpec heavy = make_grid(GridSpec{14, 14, 0.57, true, true});
  heavy.mass_scale[0] = 3;
  const Model varied = compile_model(heavy, p);
  EXPECT_TRUE(std::isnan(exact_stability(varied, varied.spec().rest, p, tight).unfactored.mode_unstable_from));
}

}  // namespace
}  // namespace dampbound
