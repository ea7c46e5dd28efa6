// Rayleigh damping from the spectrum against independent dense computations: the asked ratios
// at both frequencies, the default band against the dense eigenvalues of M^-1 K, and the
// stability verdict against the spectral radius of the dense amplification matrix.
#include "core/analysis/rayleigh_design.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "dampbound/physics/error.hpp"
#include "dampbound/physics/stiffness.hpp"
#include "tests/core/dense_step.hpp"

namespace dampbound {
namespace {

/// A 4 x 4 anchored plane; random masses and stiffnesses when `random`; a load on node 6.
SceneSpec plane(std::mt19937& rng, bool random) {
  std::uniform_real_distribution<double> u(0.5, 2.0);
  SceneSpec s;
  const int n = 4;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = add_node(s.model, Vec3(a * 0.57, 0, b * 0.57));
      s.model.anchor_scale[static_cast<size_t>(i)] = 1;
      if (random) s.model.mass_scale[static_cast<size_t>(i)] = u(rng);
    }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = a * n + b;
      if (a + 1 < n) add_spring(s.model, i, i + n, random ? u(rng) : 1.0);
      if (b + 1 < n) add_spring(s.model, i, i + 1, random ? u(rng) : 1.0);
      if (a + 1 < n && b + 1 < n) add_spring(s.model, i, i + n + 1, random ? u(rng) : 1.0);
    }
  s.model.external_force[6] = Vec3(0, -0.003, 0.004);
  s.params.m = s.params.kappa = 0.001;
  s.params.gamma = 0.0005;
  s.params.dt = 0.2;
  return s;
}

/// Spectral radius of the paper's step at rest with q's damping (tests/core/dense_step.hpp).
double dense_radius_of(const SceneSpec& scene, const Params& q) {
  return test::dense_step_radius(compile_model(scene.model, q), q.dt);
}

/// The eigenvalues of M^-1 K at rest, dense.
Eigen::VectorXd dense_lambdas(const SceneSpec& scene, const Params& p) {
  const Model model = compile_model(scene.model, p);
  const Eigen::MatrixXd A =
      Eigen::MatrixXd(mass_weighted(model, tangent_stiffness(model, model.spec().rest)));
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues();
}

TEST(RayleighDesign, PairReproducesTheAskedRatiosAtBothFrequencies) {
  const double cases[][4] = {{0.5, 0.02, 3.0, 0.05}, {0.01, 0.1, 0.2, 0.1}, {1, 0.3, 1.5, 0.4}};
  for (const auto& c : cases) {
    const auto [alpha, beta] = rayleigh_pair(c[0], c[1], c[2], c[3]);
    EXPECT_NEAR(rayleigh_zeta(alpha, beta, c[0]), c[1], 1e-9 * c[1]);
    EXPECT_NEAR(rayleigh_zeta(alpha, beta, c[2]), c[3], 1e-9 * c[3]);
  }
}

TEST(RayleighDesign, DefaultBandIsTheSpectrumsEnds) {
  std::mt19937 rng(2);
  const SceneSpec s = plane(rng, true);
  const RayleighDesign d = rayleigh_from_spectrum(s, s.params, {0.05, 0.05});
  const Eigen::VectorXd l = dense_lambdas(s, s.params);
  EXPECT_NEAR(d.lambda_min, l.minCoeff(), 1e-9 * l.maxCoeff());
  EXPECT_NEAR(d.lambda_max, l.maxCoeff(), 1e-9 * l.maxCoeff());
  const double two_pi = 6.283185307179586;
  EXPECT_NEAR(d.f1, std::sqrt(l.minCoeff()) / two_pi, 1e-9 * d.f1);
  EXPECT_NEAR(d.f2, std::min(std::sqrt(l.maxCoeff()) / two_pi, 1 / (2 * s.params.dt)), 1e-9 * d.f2);
  EXPECT_NEAR(rayleigh_zeta(d.alpha, d.beta, d.f1), 0.05, 1e-9 * 0.05);
  EXPECT_NEAR(rayleigh_zeta(d.alpha, d.beta, d.f2), 0.05, 1e-9 * 0.05);
  // The load on node 6: |f| / (alpha m_6).
  EXPECT_EQ(d.terminal_node, 6);
  EXPECT_NEAR(d.terminal_velocity, 0.005 / (d.alpha * 0.001 * s.model.mass_scale[6]), 1e-12);
}

TEST(RayleighDesign, VerdictMatchesTheDenseAmplificationMatrix) {
  std::mt19937 rng(4);
  struct Case {
    bool random;
    double kd, zeta1, zeta2;
  } cases[] = {{false, 0, 0.05, 0.05}, {false, 0, 2.5, 2.5}, {true, 0, 0.1, 0.15},
               {true, 0.0004, 0.05, 0.07}, {true, 0.0004, 3.0, 3.0}};
  int stable = 0, unstable = 0;
  for (const Case& c : cases) {
    SceneSpec s = plane(rng, c.random);
    s.params.kd = c.kd;
    const RayleighDesign d = rayleigh_from_spectrum(s, s.params, {c.zeta1, c.zeta2});
    ASSERT_TRUE(d.feasible) << c.zeta1 << " " << c.zeta2;
    Params q = s.params;
    q.rayleigh_mass = d.alpha;
    q.rayleigh_stiffness = d.beta;
    EXPECT_EQ(d.stable, dense_radius_of(s, q) < 1) << c.zeta2;
    (d.stable ? stable : unstable) += 1;
    // beta_max is the edge: stable just below, unstable just above (0: alpha, gamma and kd
    // are already unstable).
    q.rayleigh_stiffness = d.beta_max * (1 - 1e-6);
    if (d.beta_max > 0) {
      EXPECT_LT(dense_radius_of(s, q), 1);
    }
    q.rayleigh_stiffness = d.beta_max * (1 + 1e-6);
    EXPECT_GT(dense_radius_of(s, q), 1);
    // SPEC 10's closed form where C^ commutes with A (uniform masses, no dashpot).
    if (!c.random && c.kd == 0) {
      ASSERT_FALSE(std::isnan(d.beta_max_closed));
      EXPECT_NEAR(d.beta_max_closed, d.beta_max, 1e-8 * d.beta_max);
    } else {
      EXPECT_TRUE(std::isnan(d.beta_max_closed));
    }
    EXPECT_NEAR(rayleigh_zeta(d.alpha, d.beta_max, d.f2), d.zeta2_at_beta_max, 1e-12);
  }
  EXPECT_GT(stable, 0);
  EXPECT_GT(unstable, 0);
}

TEST(RayleighDesign, BadRequestsAreInputErrors) {
  std::mt19937 rng(1);
  const SceneSpec s = plane(rng, false);
  EXPECT_THROW(rayleigh_from_spectrum(s, s.params, {0, 0.1}), InputError);
  RayleighRequest r;
  r.f1 = 2;
  r.f2 = 1;
  EXPECT_THROW(rayleigh_from_spectrum(s, s.params, r), InputError);
}

}  // namespace
}  // namespace dampbound
