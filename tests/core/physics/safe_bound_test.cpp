#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// Tests of core/safe_bound: the O(springs) row sums against the dense mass-weighted tangent
// stiffness, SPEC 9's numbers on the paper plane, the property that the safe policy keeps the
// dense linearised step's spectral radius <= 1 on random small meshes (and that just outside
// the bound it can exceed 1), the policy in step(), and a cut.
#include "core/physics/safe_bound.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/linear_stability_modes.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/step.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {
namespace {

SceneSpec shipped(const std::string& name) {
  return load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/" + name + ".toml");
}

/// max over each free node's three rows of sum_s |A_rs|, from the dense A = M^-1/2 K M^-1/2.
std::vector<double> dense_row_sums(const Model& m, const std::vector<Vec3>& x) {
  const Eigen::MatrixXd A = Eigen::MatrixXd(mass_weighted(m, tangent_stiffness(m, x)));
  std::vector<double> R(m.spec().rest.size(), 0.0);
  const std::vector<int> block = free_blocks(m);
  for (size_t i = 0; i < R.size(); ++i)
    if (block[i] >= 0)
      for (int r = 0; r < 3; ++r)
        R[i] = std::max(R[i], A.row(3 * block[i] + r).cwiseAbs().sum());
  return R;
}

double dense_rho(const Model& m, const std::vector<Vec3>& x, const std::vector<double>& gamma,
                 double dt) {
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, x));
  return amplification_matrix_dense(Integrator::semi_implicit_euler, A, damping_rates(m, gamma),
                                    dt)
      .eigenvalues()
      .cwiseAbs()
      .maxCoeff();
}

/// A random small mesh in a deformed state with K positive semi-definite: random masses,
/// stiffnesses, anchors and fixed nodes; every spring stretched (l >= l0), so each spring's
/// block is PSD. Every third mesh is one free node tied along the axes to fixed nodes, where
/// A is diagonal and Gershgorin is exact.
struct RandomMesh {
  Model model;
  std::vector<Vec3> x;
};

RandomMesh random_mesh(std::mt19937& rng, int draw) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ModelSpec m;
  if (draw % 3 == 2) {
    add_node(m, Vec3::Zero());
    const Vec3 axes[] = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitX()};
    for (const Vec3& a : axes) {
      const int k = add_node(m, a * (0.5 + u(rng)));
      m.fixed[static_cast<size_t>(k)] = 1;
      add_spring(m, 0, k, 0.2 + 5 * u(rng));
    }
    m.anchor_scale[0] = u(rng) < 0.5 ? 0.0 : 3 * u(rng);
  } else {
    const int n = 2 + static_cast<int>(u(rng) * 6);
    for (int i = 0; i < n; ++i) add_node(m, Vec3(u(rng), u(rng), u(rng)) * 2.0);
    for (int i = 0; i < n; ++i) {
      m.mass_scale[static_cast<size_t>(i)] = 0.2 + 3 * u(rng);
      m.gamma_scale[static_cast<size_t>(i)] = 0.05 + 2 * u(rng);
      if (u(rng) < 0.5) m.anchor_scale[static_cast<size_t>(i)] = 0.1 + 3 * u(rng);
      if (u(rng) < 0.2) m.fixed[static_cast<size_t>(i)] = 1;
    }
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (u(rng) < 0.6) add_spring(m, i, j, 0.2 + 5 * u(rng));
  }
  Params p;
  p.m = 0.001 + 0.01 * u(rng);
  p.kappa = 0.001 + 0.5 * u(rng);
  std::vector<Vec3> x = m.rest;
  for (size_t i = 0; i < x.size(); ++i)
    if (!m.fixed[i]) x[i] += Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * 0.6;
  for (Spring& s : m.springs)  // stretched at x: l0 <= l
    s.rest_length = (x[static_cast<size_t>(s.j)] - x[static_cast<size_t>(s.i)]).norm() *
                    (u(rng) < 0.2 ? 0.0 : 0.3 + 0.7 * u(rng));
  return RandomMesh{compile_model(std::move(m), p), std::move(x)};
}

TEST(SafeBound, RowSumsMatchTheDenseMassWeightedStiffness) {
  std::mt19937 rng(3);
  for (int draw = 0; draw < 60; ++draw) {
    const RandomMesh r = random_mesh(rng, draw);
    std::vector<double> R;
    EXPECT_EQ(safe_row_sums(r.model, r.x, R), 0);  // all stretched
    const std::vector<double> D = dense_row_sums(r.model, r.x);
    for (size_t i = 0; i < R.size(); ++i) EXPECT_NEAR(R[i], D[i], 1e-12 * (1 + D[i])) << draw;
  }
}

TEST(SafeBound, PaperPlaneMatchesSpec9) {
  SceneSpec s = shipped("paper-plane");
  Params p = s.params;
  p.m = p.kappa = 0.001;
  p.dt = 0.05;
  const Model m = compile_model(s.model, p);
  std::vector<double> R;
  safe_row_sums(m, m.spec().rest, R);
  EXPECT_NEAR(R[18 * 36 + 18], 9.0, 1e-12);  // interior node: 9 kappa/m
  p.gamma = 0.002;
  const Model mg = compile_model(s.model, p);
  const SafeBoundSummary sum = safe_bound_summary(mg, mg.spec().rest, p.dt);
  EXPECT_EQ(sum.free_nodes, 1296);
  EXPECT_NEAR(sum.gamma_safe, 0.039775, 1e-12);
  EXPECT_TRUE(sum.infeasible.empty());
  EXPECT_EQ(sum.gamma_over, 0);
  // Above the interior nodes' gamma_safe, below the edges': the interior is counted, node by
  // node from R (gamma_i >= gamma_safe_i is "not guaranteed").
  Params over = p;
  over.gamma = 0.0399;
  const Model mo = compile_model(s.model, over);
  int expected_over = 0;
  for (size_t i = 0; i < R.size(); ++i)
    if (!mo.spec().fixed[i]) expected_over += !(mo.gamma[i] < safe_gamma(mo.mass[i], p.dt, R[i]));
  EXPECT_GT(expected_over, 1000);
  EXPECT_LT(expected_over, 1296);
  EXPECT_EQ(safe_bound_summary(mo, mo.spec().rest, p.dt).gamma_over, expected_over);
  const LinearLimits exact = linear_limits(max_stiffness_eigenvalue(mg, mg.spec().rest), p.m, p.dt);
  EXPECT_NEAR(exact.gamma_max, 0.039805, 5e-7);
  EXPECT_LT(sum.gamma_safe, exact.gamma_max);
  p.gamma = 0;
  const Model m0 = compile_model(s.model, p);
  EXPECT_NEAR(safe_bound_summary(m0, m0.spec().rest, p.dt).dt_safe, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(exact.dt_max_undamped, 0.7155, 5e-5);
  // At dt = 0.6 an interior node has gamma_safe = 2m/dt - m dt 9/2 = 0.00063 < gamma_lo =
  // 0.002: critical damping cannot be guaranteed there; the dt_safe at gamma_lo would.
  const SafeBoundSummary at_big_dt = safe_bound_summary(m0, m0.spec().rest, 0.6);
  EXPECT_GT(at_big_dt.infeasible.size(), 1000u);
  EXPECT_NEAR(at_big_dt.infeasible_dt[0], safe_dt(0.001, 0.002, R[at_big_dt.infeasible[0]]), 0);
  EXPECT_LT(at_big_dt.infeasible_dt[0], 0.6);
}

// gamma_safe is the user's gamma: with the middle square damped 3x (gamma_i = 3 gamma there)
// the bound is a third of the square's gamma_safe_i, not the smallest gamma_safe_i itself
// (that would be 3x above the exact limit on that plane).
TEST(SafeBound, TheSummarysGammaSafeIsTheUsersGamma) {
  SceneSpec s = shipped("paper-plane");
  Params p = s.params;
  p.m = p.kappa = 0.001;
  p.dt = 0.05;
  p.gamma = 0.002;
  const Model plain = compile_model(s.model, p);
  const SafeBoundSummary unscaled = safe_bound_summary(plain, plain.spec().rest, p.dt);
  EXPECT_FALSE(unscaled.gamma_scaled);
  EXPECT_NEAR(unscaled.gamma_safe, 0.039775, 1e-12);
  for (int a = 12; a <= 24; ++a)
    for (int b = 12; b <= 24; ++b) s.model.gamma_scale[static_cast<size_t>(a * 36 + b)] = 3;
  const Model m = compile_model(s.model, p);
  const SafeBoundSummary sum = safe_bound_summary(m, m.spec().rest, p.dt);
  EXPECT_TRUE(sum.gamma_scaled);
  EXPECT_NEAR(sum.gamma_safe, 0.039775 / 3, 1e-12);
  EXPECT_EQ(m.spec().gamma_scale[static_cast<size_t>(sum.gamma_node)], 3);
  // Just below it every node holds and the paper's step is stable; the exact limit lies above.
  Params below = p;
  below.gamma = 0.999 * sum.gamma_safe;
  const Model mb = compile_model(s.model, below);
  EXPECT_EQ(safe_bound_summary(mb, mb.spec().rest, p.dt).gamma_over, 0);
  const ExactStability e = exact_stability(mb, mb.spec().rest, below);
  EXPECT_TRUE(e.stable);
  EXPECT_GT(e.gamma_hi, sum.gamma_safe);
  EXPECT_LT(e.gamma_hi, 0.039775 / 3 * 1.01);
  // An undamped node (scale 0) limits no gamma, unless no gamma can make it hold.
  EXPECT_EQ(safe_user_gamma(0.04, 2), 0.02);
  EXPECT_TRUE(std::isinf(safe_user_gamma(0.04, 0)));
  EXPECT_EQ(safe_user_gamma(-0.001, 0), -0.001);
}

/// The property of SPEC 9 on many random meshes: the safe policy's damping keeps the dense
/// spectral radius of the linearised step at most 1 (dt below 2/sqrt(R_i) everywhere, so that
/// gamma_safe_i > 0); with every node's damping rate 2% beyond gamma_safe it exceeds 1 on
/// some meshes (the bound is not vacuous).
TEST(SafeBound, SafePolicyKeepsTheLinearisedStepStableOnRandomMeshes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int meshes = 0, beyond_unstable = 0, infeasible_nodes = 0, clamped_down = 0;
  for (int draw = 0; draw < 300; ++draw) {
    RandomMesh r = random_mesh(rng, draw);
    Model& m = r.model;
    std::vector<double> R;
    safe_row_sums(m, r.x, R);
    double r_max = 0;
    for (double v : R) r_max = std::max(r_max, v);
    if (!(r_max > 0)) continue;
    const double dt = 2.0 / std::sqrt(r_max) * (0.05 + 0.94 * u(rng));
    const double user = std::exp(std::log(1e-5) + u(rng) * std::log(1e7));  // 1e-5 .. 1e2
    std::vector<double> gamma(m.spec().rest.size(), 0.0), beyond(m.spec().rest.size(), 0.0);
    for (size_t i = 0; i < gamma.size(); ++i) {
      if (m.spec().fixed[i]) continue;
      const double safe = safe_gamma(m.mass[i], dt, R[i]);
      ASSERT_GT(safe, 0);
      const DampingChoice c = effective_damping(DampingPolicy::safe, user * m.spec().gamma_scale[i],
                                                m.lower_bound[i], HUGE_VAL, 1, safe);
      gamma[i] = c.gamma;
      infeasible_nodes += c.unguaranteed;
      clamped_down += user * m.spec().gamma_scale[i] > safe;
      EXPECT_LE(c.gamma, safe);
      beyond[i] = 1.02 * safe;
    }
    ++meshes;
    const double rho = dense_rho(m, r.x, gamma, dt);
    EXPECT_LE(rho, 1 + 1e-9) << "draw " << draw << " dt " << dt << " user gamma " << user;
    beyond_unstable += dense_rho(m, r.x, beyond, dt) > 1 + 1e-9;
  }
  EXPECT_GT(meshes, 250);
  EXPECT_GT(infeasible_nodes, 0);
  EXPECT_GT(clamped_down, 0);
  EXPECT_GT(beyond_unstable, 0);
  std::printf("[ safe bound ] %d meshes stable under safe; %d unstable 2%% beyond it\n", meshes,
              beyond_unstable);
}

TEST(SafeBound, StepUnderSafePolicyClampsAnAbsurdDamping) {
  SceneSpec s = shipped("paper-plane");
  Params p = s.params;
  p.gamma = 1.0;
  p.policy = DampingPolicy::safe;
  const Model m = compile_model(s.model, p);
  State st = initial_state(s);
  StepWorkspace ws;
  const StepStats stats = step(m, p, st, ws);
  EXPECT_EQ(stats.unguaranteed, 0);
  EXPECT_EQ(stats.compressed_springs, 0);
  const NodeSample w = sample_node(m, st, ws, s.watched);
  EXPECT_LT(w.gamma_eff, 0.0398);
  EXPECT_EQ(w.gamma_eff, w.safe);
  for (size_t i = 0; i < ws.gamma_eff.size(); ++i) EXPECT_EQ(ws.gamma_eff[i], ws.safe_bound[i]);
}

TEST(SafeBound, FollowsACutAtTheNextStep) {
  SceneSpec s = shipped("paper-plane");
  const Model whole = compile_model(s.model, s.params);
  State st = rest_state(whole);
  StepWorkspace ws;
  step(whole, s.params, st, ws);
  const std::vector<double> before = ws.safe_bound;
  std::vector<int> incident;  // every spring of the node (18, 18)
  for (int k = 0; k < s.model.spring_count(); ++k)
    if (s.model.springs[static_cast<size_t>(k)].i == 18 * 36 + 18 ||
        s.model.springs[static_cast<size_t>(k)].j == 18 * 36 + 18)
      incident.push_back(k);
  const Model cut = compile_model(without_springs(s.model, incident), s.params);
  EXPECT_EQ(incident.size(), 6u);  // 4 along the axes, 2 diagonals
  EXPECT_EQ(cut.spec().spring_count(), whole.spec().spring_count() - 6);
  step(cut, s.params, st, ws);
  EXPECT_GT(ws.safe_bound[18 * 36 + 18], before[18 * 36 + 18]);
  EXPECT_GT(ws.safe_bound[19 * 36 + 19], before[19 * 36 + 19]);  // its diagonal neighbour
  EXPECT_EQ(ws.safe_bound[18 * 36 + 19], before[18 * 36 + 19]);  // x rows still sum to 9
  EXPECT_EQ(ws.safe_bound[5], before[5]);
}

}  // namespace
}  // namespace dampbound
