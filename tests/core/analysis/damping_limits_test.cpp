// SPEC 10's exact limits and generalised safe bound against the dense amplification matrix of
// the paper's step on small meshes with dashpots and Rayleigh damping.
#include "core/analysis/damping_limits.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/mass_scaling.hpp"
#include "core/analysis/mass_scaling_scene.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/stiffness.hpp"

namespace dampbound {
namespace {

/// An n x n plane (spacing 0.57, diagonals, anchors), masses and stiffnesses scaled at random.
ModelSpec plane(int n, std::mt19937& rng, bool random_scales) {
  std::uniform_real_distribution<double> u(0.5, 2.0);
  ModelSpec s;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = add_node(s, Vec3(a * 0.57, 0, b * 0.57));
      s.anchor_scale[static_cast<size_t>(i)] = 1;
      if (random_scales) s.mass_scale[static_cast<size_t>(i)] = u(rng);
    }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = a * n + b;
      if (a + 1 < n) add_spring(s, i, i + n, random_scales ? u(rng) : 1.0);
      if (b + 1 < n) add_spring(s, i, i + 1, random_scales ? u(rng) : 1.0);
      if (a + 1 < n && b + 1 < n) add_spring(s, i, i + n + 1, random_scales ? u(rng) : 1.0);
    }
  if (random_scales)
    for (Spring& sp : s.springs) sp.kd_scale = u(rng);
  return s;
}

/// Spectral radius of the paper's step linearised at x with gamma_i given per node.
double radius(const Model& model, const std::vector<Vec3>& x, const std::vector<double>& gamma,
              double dt) {
  const Eigen::MatrixXd K = Eigen::MatrixXd(tangent_stiffness(model, x));
  std::vector<double> zero(model.spec().rest.size(), 0.0);
  Eigen::MatrixXd C = Eigen::MatrixXd(spring_damping_matrix(model, x));
  const long n = K.rows();
  Eigen::VectorXd minv(n);
  for (size_t i = 0, b = 0; i < model.spec().rest.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    for (int r = 0; r < 3; ++r) {
      minv(static_cast<long>(3 * b + r)) = 1 / model.mass[i];
      C(static_cast<long>(3 * b + r), static_cast<long>(3 * b + r)) += gamma[i];
    }
    ++b;
  }
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd MK = minv.asDiagonal() * K, MC = minv.asDiagonal() * C;
  Eigen::MatrixXd T(2 * n, 2 * n);
  // v' = (I - dt M^-1 C) v - dt M^-1 K x;  x' = x + dt v'
  T.topLeftCorner(n, n) = I - dt * dt * MK;
  T.topRightCorner(n, n) = dt * (I - dt * MC);
  T.bottomLeftCorner(n, n) = -dt * MK;
  T.bottomRightCorner(n, n) = I - dt * MC;
  return T.eigenvalues().cwiseAbs().maxCoeff();
}

std::vector<double> scaled(const Model& model, double gamma) {
  std::vector<double> g(model.spec().rest.size());
  for (size_t i = 0; i < g.size(); ++i) g[i] = gamma * model.spec().gamma_scale[i];
  return g;
}

TEST(DampingLimits, ExactLimitsMatchTheDenseAmplificationMatrix) {
  std::mt19937 rng(3);
  struct Case {
    double kd, alpha, beta;
    bool random;
  } cases[] = {{0.002, 0, 0, false}, {0.002, 0.1, 0.01, true}, {0, 0.2, 0.05, false},
               {0.01, 0, 0.02, true}};
  for (const Case& c : cases) {
    Params p;
    p.kd = c.kd;
    p.rayleigh_mass = c.alpha;
    p.rayleigh_stiffness = c.beta;
    p.gamma = 0.001;
    const Model model = compile_model(plane(4, rng, c.random), p);
    const std::vector<Vec3> x = model.spec().rest;
    const GeneralLimits g = general_limits(model, x, p);
    ASSERT_GT(g.dt_max, 0);
    EXPECT_LE(radius(model, x, scaled(model, p.gamma), g.dt_max * 0.999), 1 + 1e-9);
    EXPECT_GT(radius(model, x, scaled(model, p.gamma), g.dt_max * 1.001), 1 + 1e-6);
    if (g.gamma_max > 0) {
      EXPECT_LE(radius(model, x, scaled(model, g.gamma_max * 0.999), p.dt), 1 + 1e-9);
      EXPECT_GT(radius(model, x, scaled(model, g.gamma_max * 1.001), p.dt), 1 + 1e-6);
    }
  }
}

TEST(DampingLimits, TheIssuesPlaneNumbers) {
  // 8 x 8 paper plane, m = kappa = 0.001: kd = 0.002 alone, against nodal gamma = 0.002.
  std::mt19937 rng(1);
  Params p;
  p.gamma = 0;
  p.kd = 0.002;
  const Model dashpot = compile_model(plane(8, rng, false), p);
  EXPECT_NEAR(general_limits(dashpot, dashpot.spec().rest, p).dt_max, 0.1289, 5e-4);
}

TEST(DampingLimits, SafeBoundHoldsOnRandomMeshes) {
  // Stretched (every spring in tension, so K is positive semi-definite and SPEC 9 applies) and
  // jittered meshes, at a dt inside every node's safe range: the safe policy's gamma_i and
  // dt_safe keep the dense amplification matrix's radius at most 1. No trial is skipped.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  int checked = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Params p;
    p.kd = 0.01 * u(rng);
    p.rayleigh_mass = 0.5 * u(rng);
    p.rayleigh_stiffness = 0.05 * u(rng);
    const Model model = compile_model(plane(3, rng, true), p);
    std::vector<Vec3> x = model.spec().rest;
    for (Vec3& xi : x) xi = 1.05 * xi + 0.005 * Vec3(u(rng), u(rng), u(rng));
    ASSERT_TRUE(psd_floor(model, x).has_value()) << "trial " << trial;
    const DampedSafeRows rows(model, x);
    double dt_cap = 1e300;  // the largest dt every node's margin allows at gamma_i = 0
    for (size_t i = 0; i < x.size(); ++i)
      if (!model.spec().fixed[i]) dt_cap = std::min(dt_cap, rows.dt_safe(static_cast<int>(i), 0.0));
    ASSERT_TRUE(dt_cap > 0 && dt_cap < 1e300) << "trial " << trial;
    p.dt = dt_cap * (0.2 + 0.7 * u(rng));
    std::vector<double> gamma(model.spec().rest.size(), 0.0);
    for (size_t i = 0; i < gamma.size(); ++i) {
      if (model.spec().fixed[i]) continue;
      const double safe = rows.gamma_safe(static_cast<int>(i), p.dt);
      ASSERT_GT(safe, 0) << "trial " << trial << " node " << i;
      gamma[i] = safe * u(rng);  // the safe policy keeps gamma_i below gamma_safe_i
    }
    EXPECT_LE(radius(model, x, gamma, p.dt), 1 + 1e-9) << "trial " << trial;
    // dt_safe at those gammas: every node holds, so the step is stable there too.
    double dt = 1e300;
    for (size_t i = 0; i < gamma.size(); ++i)
      if (!model.spec().fixed[i]) dt = std::min(dt, rows.dt_safe(static_cast<int>(i), gamma[i]));
    EXPECT_GE(dt, p.dt * (1 - 1e-12));
    EXPECT_LE(radius(model, x, gamma, dt * 0.999), 1 + 1e-9) << "trial " << trial;
    ++checked;
  }
  EXPECT_EQ(checked, 20);
}

TEST(DampingLimits, ZeroDampingKeepsSpec9) {
  std::mt19937 rng(5);
  Params p;
  const Model model = compile_model(plane(3, rng, true), p);
  EXPECT_FALSE(model.spring_damping);
  std::vector<double> R;
  safe_row_sums(model, model.spec().rest, R);
  const DampedSafeRows rows(model, model.spec().rest);
  for (size_t i = 0; i < R.size(); ++i) {
    EXPECT_NEAR(rows.gamma_safe(static_cast<int>(i), p.dt), safe_gamma(model.mass[i], p.dt, R[i]),
                1e-12 * model.mass[i] / p.dt);
    EXPECT_NEAR(rows.dt_safe(static_cast<int>(i), 0.002), safe_dt(model.mass[i], 0.002, R[i]), 1e-12);
  }
}

// The factorisation budget reaches SPEC 10's own factorisations (the index, lambda_min(C^),
// both limit searches, a kind's range, mass scaling): over it they throw before any numeric
// factorisation, the exact analysis reports "over budget" instead of throwing, and a budget
// that holds gives the bits of no budget at all.
TEST(DampingLimits, TheFactorisationBudgetBoundsTheDampedAnalysis) {
  std::mt19937 rng(7);
  const ModelSpec spec = plane(16, rng, true);  // 768 rows: sparse Cholesky, not dense
  Params p;
  p.m = p.kappa = 0.001;
  p.gamma = 0.002;
  p.kd = 0.001;
  p.dt = 0.05;
  const Model model = compile_model(spec, p);
  const std::vector<Vec3>& x = spec.rest;
  const double tiny = 1e3;  // flops: below any factorisation of these matrices
  EXPECT_THROW(general_limits(model, x, p, tiny), FactorisationOverBudget);
  EXPECT_THROW(damping_kind_max(spec, x, p, DampingKind::dashpot, tiny), FactorisationOverBudget);
  // A pattern analysed for an earlier search without a budget does not let a later one past
  // its own (SharedFactors: the damping kinds of suggest), and the kinds shared give the
  // numbers of the kinds alone.
  SharedFactors shared;
  const double nodal = damping_kind_max(spec, x, p, DampingKind::nodal, kUnboundedFactor, &shared);
  EXPECT_EQ(nodal, damping_kind_max(spec, x, p, DampingKind::nodal));
  EXPECT_THROW(damping_kind_max(spec, x, p, DampingKind::dashpot, tiny, &shared),
               FactorisationOverBudget);
  EXPECT_EQ(damping_kind_max(spec, x, p, DampingKind::rayleigh_mass, kUnboundedFactor, &shared),
            damping_kind_max(spec, x, p, DampingKind::rayleigh_mass));
  Params rayleigh = p;
  rayleigh.kd = 0;
  rayleigh.gamma = 0;
  rayleigh.rayleigh_mass = 0.01;
  rayleigh.rayleigh_stiffness = 0.001;  // C^ commutes: closed forms on a certified spectrum
  EXPECT_THROW(general_limits(compile_model(spec, rayleigh), x, rayleigh, tiny),
               FactorisationOverBudget);

  const GeneralLimits free = general_limits(model, x, p);
  const GeneralLimits held = general_limits(model, x, p, kDefaultFactorBudget);
  EXPECT_EQ(held.index, free.index);
  EXPECT_EQ(held.gamma_max, free.gamma_max);
  EXPECT_EQ(held.dt_max, free.dt_max);
  EXPECT_GT(free.dt_max, 0);

  ExactOptions over;
  over.max_factor_flops = tiny;
  const ExactStability e = exact_stability(model, x, p, over);
  EXPECT_FALSE(e.computed());
  EXPECT_FALSE(e.spec10);
  EXPECT_NE(e.over_budget_reason().find("over the budget"), std::string::npos);

  const MassScalingProblem problem = mass_scaling_problem(model);
  MassScalingOptions o;
  o.max_factor_flops = tiny;
  EXPECT_THROW(mass_scaling(problem, 2 * free.dt_max, o), FactorisationOverBudget);
}

}  // namespace
}  // namespace dampbound

namespace dampbound {
namespace {

TEST(DampingLimits, StepsOnePassEqualsTheRows) {
  std::mt19937 rng(17);
  Params p;
  p.kd = 0.003;
  p.rayleigh_mass = 0.2;
  p.rayleigh_stiffness = 0.01;
  const Model model = compile_model(plane(4, rng, true), p);
  std::vector<Vec3> x = model.spec().rest;
  for (Vec3& xi : x) xi += Vec3(0.03, -0.02, 0.01);
  x[5] += Vec3(0.1, 0.2, -0.1);
  std::vector<double> g;
  damped_safe_gammas(model, x, p.dt, g);
  const DampedSafeRows rows(model, x);
  for (size_t i = 0; i < g.size(); ++i) EXPECT_EQ(g[i], rows.gamma_safe(static_cast<int>(i), p.dt));
}

TEST(DampingLimits, WeylsFloorIsBelowTheSmallestDampingRate) {
  // damping_floor against the dense lambda_min(C^) on planes with dashpots, Rayleigh and
  // nodal damping (random scales, stretched so that A is not the rest's): below it, and
  // within the rest of the Weyl sum; NaN for a negative beta, whose sign it cannot use.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  int positive = 0;
  for (int trial = 0; trial < 12; ++trial) {
    Params p;
    p.kd = trial % 3 == 0 ? 0.0 : 0.004 * u(rng);
    p.rayleigh_mass = trial % 2 == 0 ? 0.0 : 0.3 * u(rng);
    p.rayleigh_stiffness = trial % 4 == 1 ? 0.0 : 0.05 * u(rng);
    p.gamma = trial % 5 == 0 ? 0.0 : 0.002 * u(rng);
    ModelSpec spec = plane(4, rng, true);
    if (trial % 2 == 1) spec.anchor_kd_scale.assign(spec.rest.size(), 1.0);
    const Model model = compile_model(spec, p);
    std::vector<Vec3> x = model.spec().rest;
    for (Vec3& q : x) q *= 1 + 0.05 * u(rng);  // stretched: every spring in tension
    const SparseMatrix A = mass_weighted(model, tangent_stiffness(model, x));
    const SparseMatrix C = weighted_damping(model, x, scaled(model, p.gamma));
    const double a_min = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(A))
                             .eigenvalues()
                             .minCoeff();
    const double c_min = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(C))
                             .eigenvalues()
                             .minCoeff();
    const double floor = damping_floor(model, p.gamma, a_min * (1 - 1e-12), A, C);
    ASSERT_FALSE(std::isnan(floor)) << trial;
    EXPECT_LE(floor, c_min) << trial;
    positive += floor > 0;
  }
  EXPECT_GT(positive, 4);
  Params p;
  p.rayleigh_stiffness = -0.01;
  p.gamma = 0.001;
  const Model model = compile_model(plane(3, rng, false), p);
  const std::vector<Vec3> x = model.spec().rest;
  const SparseMatrix A = mass_weighted(model, tangent_stiffness(model, x));
  EXPECT_TRUE(std::isnan(damping_floor(model, p.gamma, 0.0, A,
                                       weighted_damping(model, x, scaled(model, p.gamma)))));
}

TEST(DampingLimits, TheFloorAndTheSpectrumsFactorsLeaveTheLimitsAlone) {
  // exact_stability hands its spectrum's factors and Weyl's floor to general_limits: the
  // same index, gamma and dt limits, to the bit, as general_limits on its own, and a
  // damping_min of the same sign as the certified eigenvalue's.
  std::mt19937 rng(9);
  Params p;
  p.kd = 0.0005;
  p.rayleigh_mass = 0.01;
  p.rayleigh_stiffness = 0.01;
  p.gamma = 0.002;
  p.dt = 0.05;
  const Model model = compile_model(plane(24, rng, false), p);
  const std::vector<Vec3> x = model.spec().rest;
  const ExactStability e = exact_stability(model, x, p);
  ASSERT_TRUE(e.spec10);
  const GeneralLimits alone = general_limits(model, x, p);
  EXPECT_EQ(e.general.index, alone.index);
  EXPECT_EQ(e.general.gamma_max, alone.gamma_max);
  EXPECT_EQ(e.general.dt_max, alone.dt_max);
  const SparseMatrix C = weighted_damping(model, x, scaled(model, p.gamma));
  const double c_min = certified_smallest_eigenvalue(C).lo;
  EXPECT_GT(c_min, 0);
  EXPECT_GT(e.general.damping_min, 0);
  EXPECT_LE(e.general.damping_min, c_min);
}

}  // namespace
}  // namespace dampbound
