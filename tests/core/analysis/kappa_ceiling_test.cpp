// Stiffness ceilings against independent dense computations: the factor against a bisection on
// the spectral radius of the dense amplification matrix of the paper's step (no index theory),
// runs at 0.98x and 1.02x of it, and the contact ceiling's closed form against the dense rows
// of SPEC 10's Q with the contact spring added.
#include "core/analysis/kappa_ceiling.hpp"

#include <gtest/gtest.h>

#include <random>

#include "dampbound/physics/error.hpp"
#include "dampbound/physics/stiffness.hpp"
#include "tests/core/dense_step.hpp"

namespace dampbound {
namespace {

/// A 4 x 4 plane (spacing 0.57, diagonals, anchors) with random masses and stiffnesses, node 5
/// pulled 0.05 cm along y, and one box region over a 2 x 2 corner.
SceneSpec small_scene(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.5, 2.0);
  SceneSpec s;
  const int n = 4;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = add_node(s.model, Vec3(a * 0.57, 0, b * 0.57));
      s.model.anchor_scale[static_cast<size_t>(i)] = u(rng);
      s.model.mass_scale[static_cast<size_t>(i)] = u(rng);
    }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = a * n + b;
      if (a + 1 < n) add_spring(s.model, i, i + n, u(rng));
      if (b + 1 < n) add_spring(s.model, i, i + 1, u(rng));
      if (a + 1 < n && b + 1 < n) add_spring(s.model, i, i + n + 1, u(rng));
    }
  s.model.fixed[0] = 1;
  s.params.m = s.params.kappa = 0.001;
  s.params.gamma = 0.002;
  s.params.dt = 0.3;
  s.perturbations.push_back({5, Vec3(0, 0.05, 0), Vec3::Zero()});
  s.rules.max_iterations = 4000;
  s.rules.reference = 0.05;
  s.regions.push_back({"corner", {0, 1, 4, 5}});
  return s;
}

/// The factor where the dense radius crosses 1, by plain bisection from [lo, hi].
double dense_factor(const SceneSpec& scene, const Params& p, const StiffnessSelection& sel,
                    double lo, double hi) {
  const auto radius = [&](double f) {
    return test::dense_step_radius(compile_model(scaled_stiffness(scene.model, sel, f), p), p.dt);
  };
  EXPECT_LT(radius(lo), 1);
  EXPECT_GT(radius(hi), 1);
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (radius(mid) < 1 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(StiffnessCeiling, FactorMatchesTheDenseAmplificationMatrix) {
  std::mt19937 rng(7);
  struct Case {
    double kd, alpha, beta;
  } cases[] = {{0, 0, 0}, {0.0001, 0, 0}, {0, 0.1, 0.02}, {0.00005, 0.05, 0.01}};
  int positive = 0;
  for (const Case& c : cases) {
    const SceneSpec scene = small_scene(rng);
    Params p = scene.params;
    p.kd = c.kd;
    p.rayleigh_mass = c.alpha;
    p.rayleigh_stiffness = c.beta;
    for (const StiffnessSelection& sel :
         {whole_selection(scene.model), region_selection(scene.model, scene.regions[0])}) {
      const StiffnessCeiling got = stiffness_ceiling(scene, p, sel, scene.rules, false);
      ASSERT_TRUE(std::isfinite(got.factor)) << sel.label;
      if (got.factor == 0) {  // unstable even without the selection: so says the dense step
        EXPECT_GT(test::dense_step_radius(compile_model(scaled_stiffness(scene.model, sel, 0), p), p.dt), 1);
        continue;
      }
      ++positive;
      const double want = dense_factor(scene, p, sel, 0.5 * got.factor, 1.5 * got.factor);
      EXPECT_NEAR(got.factor, want, 1e-7 * want) << sel.label << " kd " << c.kd;
    }
  }
  EXPECT_GE(positive, 6);
}

TEST(StiffnessCeiling, RunsAtTheEndsSettleBelowAndNotAbove) {
  std::mt19937 rng(11);
  const SceneSpec scene = small_scene(rng);
  const StiffnessCeiling c =
      stiffness_ceiling(scene, scene.params, whole_selection(scene.model), scene.rules, true);
  ASSERT_TRUE(c.ran);
  EXPECT_TRUE(c.below.verified()) << to_string(c.below.result.outcome);
  EXPECT_FALSE(c.above.verified()) << to_string(c.above.result.outcome);
  // The region's ceiling is above the whole scene's (fewer springs scaled).
  const StiffnessCeiling r = stiffness_ceiling(
      scene, scene.params, region_selection(scene.model, scene.regions[0]), scene.rules, false);
  EXPECT_GT(r.factor, c.factor);
}

TEST(StiffnessCeiling, NoStiffnessOnAFreeNodeHasNoCeiling) {
  std::mt19937 rng(1);
  SceneSpec scene = small_scene(rng);
  const StiffnessSelection none{"none", {}, {}};
  EXPECT_TRUE(std::isinf(stiffness_ceiling(scene, scene.params, none, scene.rules, true).factor));
  Params verlet = scene.params;
  verlet.integrator = Integrator::verlet;
  EXPECT_THROW(stiffness_ceiling(scene, verlet, none, scene.rules, false), InputError);
}

/// Node i's smallest Gershgorin margin of Q = 4 I - 2 dt C^ - dt^2 A with a zero-length contact
/// spring of stiffness k (dashpot kd) at node i, from dense matrices.
double dense_margin(const Model& model, int node, double k, double kd, double dt) {
  const std::vector<Vec3>& x = model.spec().rest;
  Eigen::MatrixXd A = Eigen::MatrixXd(mass_weighted(model, tangent_stiffness(model, x)));
  Eigen::MatrixXd C = Eigen::MatrixXd(weighted_damping(model, x, model.gamma));
  const std::vector<int> block = free_blocks(model);
  const long b = block[static_cast<size_t>(node)];
  const double m = model.mass[static_cast<size_t>(node)];
  for (long r = 3 * b; r < 3 * b + 3; ++r) {
    A(r, r) += k / m;
    C(r, r) += (kd + model.rayleigh_stiffness * k) / m;
  }
  const Eigen::MatrixXd Q =
      4 * Eigen::MatrixXd::Identity(A.rows(), A.cols()) - 2 * dt * C - dt * dt * A;
  double worst = std::numeric_limits<double>::infinity();
  for (long r = 3 * b; r < 3 * b + 3; ++r)
    worst = std::min(worst, 2 * Q(r, r) - Q.row(r).cwiseAbs().sum());
  return worst;
}

TEST(ContactCeiling, ClosedFormMatchesTheRows) {
  std::mt19937 rng(5);
  struct Case {
    double kd, alpha, beta, dt;
  } cases[] = {{0, 0, 0, 0.3}, {0.0002, 0.05, 0.01, 0.2}, {0.0005, 0, 0.03, 0.25}};
  for (const Case& c : cases) {
    SceneSpec scene = small_scene(rng);
    Params p = scene.params;
    p.kd = c.kd;
    p.rayleigh_mass = c.alpha;
    p.rayleigh_stiffness = c.beta;
    p.dt = c.dt;
    const Model model = compile_model(scene.model, p);
    const ContactCeilings got = contact_ceilings(model, model.spec().rest, p.dt, p.kd, 3);
    EXPECT_TRUE(std::isnan(got.k_max[0]));  // fixed
    int positive = 0;
    for (int i = 1; i < model.spec().node_count(); ++i) {
      const double k = got.k_max[static_cast<size_t>(i)];
      if (k == 0) {
        EXPECT_LE(dense_margin(model, i, 0, p.kd, p.dt), 1e-12);
        continue;
      }
      ++positive;
      EXPECT_GT(dense_margin(model, i, k * (1 - 1e-7), p.kd, p.dt), 0) << i;
      EXPECT_LT(dense_margin(model, i, k * (1 + 1e-7), p.kd, p.dt), 0) << i;
    }
    EXPECT_GT(positive, 10);
    EXPECT_EQ(got.worst.size(), 3u);
    EXPECT_EQ(got.min, got.k_max[static_cast<size_t>(got.worst[0])]);
    EXPECT_LE(got.min, got.median);
  }
}

}  // namespace
}  // namespace dampbound
