// Tests of core/analysis/detail/index_patch: the patch around the paper step's index top,
// against dense eigenvalues of the whole index matrix, and over the factorisation budget
// against the factorised analysis.
#include "core/analysis/detail/index_patch.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <tuple>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/linear_stability_modes.hpp"
#include "core/io/mesh.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {
namespace {

using detail::IndexPatch;

/// A block of nx x ny x nz nodes 0.3 cm apart, each cube cut into Kuhn's six tetrahedra, made
/// into a model as a mesh file would be (tissue-block's rules: masses lumped from the volumes,
/// van Gelder's stiffnesses, no anchors), the bottom layer (y = 0) fixed: its corner and edge
/// nodes are light, so their damping sets the index's top there.
ModelSpec lumped_block(int nx, int ny, int nz) {
  CellMesh mesh;
  const double h = 0.3;
  auto index = [&](int a, int b, int c) { return (a * ny + b) * nz + c; };
  for (int a = 0; a < nx; ++a)
    for (int b = 0; b < ny; ++b)
      for (int c = 0; c < nz; ++c) mesh.vertices.emplace_back(a * h, b * h, c * h);
  const std::array<std::array<int, 3>, 6> orders = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (int a = 0; a + 1 < nx; ++a)
    for (int b = 0; b + 1 < ny; ++b)
      for (int c = 0; c + 1 < nz; ++c)
        for (const auto& order : orders) {
          int p[3] = {a, b, c};
          MeshCell cell;
          cell.shape = CellShape::tetra;
          cell.corners.push_back(index(p[0], p[1], p[2]));
          for (int axis : order) {
            ++p[axis];
            cell.corners.push_back(index(p[0], p[1], p[2]));
          }
          const auto& v = mesh.vertices;
          if (tetra_signed_volume(v[static_cast<size_t>(cell.corners[0])],
                                  v[static_cast<size_t>(cell.corners[1])],
                                  v[static_cast<size_t>(cell.corners[2])],
                                  v[static_cast<size_t>(cell.corners[3])]) < 0)
            std::swap(cell.corners[2], cell.corners[3]);
          mesh.cells.push_back(cell);
        }
  MeshSprings how;
  how.anchors = false;
  how.density = 0.001;
  how.young = 100.0;
  ModelSpec model = model_from_mesh(mesh, how);
  for (int a = 0; a < nx; ++a)
    for (int c = 0; c < nz; ++c) model.fixed[static_cast<size_t>(index(a, 0, c))] = 1;
  return model;
}

Params tissue_params() {
  Params p;
  p.m = 1;
  p.kappa = 1;
  p.gamma = 0.02;
  p.dt = 0.0002;
  return p;
}

/// The index matrix h^2 A + 2 h gamma diag(R), dense, and what the patch needs beside A.
struct Index {
  Model model;
  std::vector<Vec3> x;
  SparseMatrix A;
  Eigen::VectorXd R;
  std::vector<double> ceiling;
  Index(const Model& m, const std::vector<Vec3>& at) : model(m), x(at) {
    A = mass_weighted(model, tangent_stiffness(model, x));
    std::vector<double> scale(model.spec().rest.size());
    for (size_t i = 0; i < scale.size(); ++i) scale[i] = model.spec().gamma_scale[i];
    R = damping_rates(model, scale);
    splitting_ceilings(model, x, ceiling);
  }
  double top(double gamma, double h) const {
    Eigen::MatrixXd S = (h * h) * Eigen::MatrixXd(A);
    S.diagonal() += (2 * h * gamma) * R;
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly)
        .eigenvalues()
        .maxCoeff();
  }
};

TEST(IndexPatch, BoundsTheIndexFromBothSidesWhereItsTopIsLocal) {
  const Model model = compile_model(lumped_block(9, 5, 7), tissue_params());
  std::vector<Vec3> stretched = model.spec().rest;
  for (Vec3& x : stretched) x.y() *= 1.05;
  for (const bool stretch : {false, true}) {
    const Index s(model, stretch ? stretched : model.spec().rest);
    // Near the paper step's limits the light corners' damping sets the top; at a small gamma
    // and dt A's own top weighs more, and the patch need not prove it tightly.
    for (const auto& [gamma, h, local] :
         std::vector<std::tuple<double, double, bool>>{{0.02, 2e-4, true},
                                                       {0.0215, 2e-4, true},
                                                       {0.02, 2.134e-4, true},
                                                       {0.005, 1e-4, false}}) {
      SCOPED_TRACE(testing::Message() << "gamma " << gamma << ", h " << h);
      const double top = s.top(gamma, h);
      const IndexPatch patch(s.model, s.x, s.A, s.R, s.ceiling, gamma, h, top * (1 - 1e-9), 3);
      ASSERT_TRUE(patch.found());
      EXPECT_LT(patch.node_count(), 120);  // of 315 nodes (45 fixed)
      // Sound below the top, and where the top is local, tight above it.
      EXPECT_FALSE(patch.proved_below(top * (1 - 1e-9), gamma, h));
      const double at_most = patch.index_at_most(gamma, h);
      EXPECT_GE(at_most, top);
      if (!local) continue;
      EXPECT_TRUE(patch.proved_below(top * (1 + 1e-8), gamma, h));
      EXPECT_LE(at_most, top * (1 + 1e-9));
      // The principal submatrix's top vector: its quotient in A is a lower bound of
      // lambda_max(A), and in the index matrix it reaches the top.
      const Eigen::VectorXd u = patch.vector(gamma, h);
      const double a = patch.rayleigh_below(u);
      const double exact_a = u.dot(s.A * u) / u.squaredNorm();
      EXPECT_LE(a, exact_a);
      EXPECT_GT(a, exact_a * (1 - 1e-12));
      const double rho = u.dot(s.R.cwiseProduct(u)) / u.squaredNorm();
      EXPECT_NEAR(h * h * exact_a + 2 * h * gamma * rho, top, 1e-9 * top);
    }
  }
}

TEST(IndexPatch, NoneWhereTheTopIsNotLocal) {
  // One mass and one rate everywhere: every interior node's bound is the same, so the seeds
  // alone are more than a patch may hold.
  Params p;
  const Model model = compile_model(make_grid(GridSpec{30, 30, 0.57, true, true}), p);
  const Index s(model, model.spec().rest);
  // A proved lower bound of the index: its largest diagonal entry (a Rayleigh quotient).
  const Eigen::VectorXd diagonal =
      (p.dt * p.dt) * Eigen::MatrixXd(s.A).diagonal() + (2 * p.dt * p.gamma) * s.R;
  const IndexPatch patch(model, model.spec().rest, s.A, s.R, s.ceiling, p.gamma, p.dt, diagonal.maxCoeff(),
                         3);
  EXPECT_FALSE(patch.found());
  EXPECT_FALSE(patch.proved_below(1e300, p.gamma, p.dt));
}

TEST(IndexPatch, NeverProvesLessThanTheDenseIndexOnRandomStatesAndRates) {
  // Random damping scales per node, states at rest, stretched, squeezed (compressed springs:
  // B+ in the bound) and shaken, and points around the limits: nothing the patch proves may
  // lie below the dense index, nor its vector's quotient above A's.
  std::mt19937 rng(20261127);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int proved = 0;
  for (int trial = 0; trial < 8; ++trial) {
    ModelSpec spec = lumped_block(6 + trial % 3, 4 + trial % 2, 5 + trial % 3);
    for (double& g : spec.gamma_scale) g = 0.5 + 1.5 * unit(rng);
    const Model model = compile_model(spec, tissue_params());
    std::vector<Vec3> x = model.spec().rest;
    const double f = 0.92 + 0.16 * unit(rng);
    for (size_t i = 0; i < x.size(); ++i) {
      x[i][trial % 3] *= f;
      if (trial >= 4 && !model.spec().fixed[i])
        x[i] += 0.01 * Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
    }
    const Index s(model, x);
    const double gamma = 0.005 + 0.03 * unit(rng), h = 1e-4 + 1.5e-4 * unit(rng);
    SCOPED_TRACE(testing::Message()
                 << "trial " << trial << ": gamma " << gamma << ", h " << h << ", scale " << f);
    const double top = s.top(gamma, h);
    for (const int layers : {1, 3}) {
      const IndexPatch patch(model, x, s.A, s.R, s.ceiling, gamma, h, top * (1 - 1e-6), layers);
      if (!patch.found()) continue;
      EXPECT_FALSE(patch.proved_below(top * (1 - 1e-10), gamma, h));
      const double at_most = patch.index_at_most(gamma, h);
      EXPECT_GE(at_most, top);
      proved += std::isfinite(at_most);
      const Eigen::VectorXd u = patch.vector(gamma, h);
      EXPECT_LE(patch.rayleigh_below(u), u.dot(s.A * u) / u.squaredNorm());
    }
  }
  EXPECT_GE(proved, 8);  // most trials found a patch and proved a bound
}

TEST(IndexPatch, OverTheBudgetItBracketsTheExactLimitsTightly) {
  const Params p = tissue_params();
  const Model model = compile_model(lumped_block(11, 7, 9), p);
  const ExactStability exact = exact_stability(model, model.spec().rest, p);
  ASSERT_TRUE(exact.computed());
  ASSERT_EQ(exact.method, ExactMethod::symmetric_index);
  // A budget under the sparse factorisation's and over one of the patch's (0.0066 GFlop for
  // its 90 nodes): the patch is used.
  ExactOptions none;
  none.max_factor_flops = 1;
  const double sparse = exact_stability(model, model.spec().rest, p, none).factor_flops;
  ExactOptions budget;
  budget.max_factor_flops = 0.99 * sparse;
  ASSERT_GT(budget.max_factor_flops, 1e7);
  const ExactStability over = exact_stability(model, model.spec().rest, p, budget);
  ASSERT_FALSE(over.computed());
  const ExactStability::Unfactored& b = over.unfactored;
  EXPECT_GT(b.patch_nodes, 0);
  EXPECT_TRUE(over.stable);
  EXPECT_EQ(b.index_at_most, b.index_patch);
  EXPECT_LT(b.index_at_most, b.index_gershgorin);
  // Both sides within 1e-10 of each other, around the factorised limit (whose certified
  // interval's upper end makes it err low, by up to ~1e-9 here), and the factorised analysis
  // agrees 1e-8 to either side.
  for (const bool gamma : {true, false}) {
    SCOPED_TRACE(gamma ? "gamma" : "dt");
    const double stable = gamma ? b.gamma_stable_hi : b.dt_stable_up_to;
    const double unstable = gamma ? b.gamma_unstable_from : b.dt_unstable_from;
    const double factorised = gamma ? exact.gamma_hi : exact.dt_max;
    EXPECT_LE(stable, unstable);
    EXPECT_LT(unstable - stable, 1e-10 * stable);
    EXPECT_GE(unstable, factorised);
    EXPECT_GT(stable, factorised * (1 - 1e-8));
    for (const double side : {stable * (1 - 1e-8), unstable * (1 + 1e-8)}) {
      Params q = p;
      (gamma ? q.gamma : q.dt) = side;
      const Model mq = compile_model(lumped_block(11, 7, 9), q);
      EXPECT_EQ(exact_stability(mq, mq.spec().rest, q).stable, side < stable) << side;
    }
  }
  // With a budget of one flop nothing is factorised, the patch included.
  EXPECT_EQ(exact_stability(model, model.spec().rest, p, none).unfactored.patch_nodes, 0);
}

TEST(IndexPatch, OverTheBudgetWhatItProvesHoldsOnRandomStatesAndRates) {
  // Random damping scales per node and a random gamma, at rest, stretched and shaken (springs
  // compressed: no stable side, the instability proofs only): every threshold the patch route
  // reports, 1e-8 to its proved side, gets the same verdict from the factorised analysis.
  std::mt19937 rng(1127);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int patches = 0, claims = 0;
  for (int trial = 0; trial < 3; ++trial) {
    ModelSpec spec = lumped_block(11, 7, 9);
    for (double& g : spec.gamma_scale) g = 0.5 + 1.5 * unit(rng);
    Params p = tissue_params();
    p.gamma = 0.01 + 0.02 * unit(rng);
    const Model model = compile_model(spec, p);
    std::vector<Vec3> x = model.spec().rest;
    for (size_t i = 0; i < x.size(); ++i) {
      if (trial == 1) x[i].y() *= 1.04;
      if (trial == 2 && !model.spec().fixed[i])
        x[i] += 0.01 * Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
    }
    SCOPED_TRACE(testing::Message() << "trial " << trial << ", gamma " << p.gamma);
    ExactOptions none;
    none.max_factor_flops = 1;
    ExactOptions budget;
    budget.max_factor_flops = 0.99 * exact_stability(model, x, p, none).factor_flops;
    const ExactStability over = exact_stability(model, x, p, budget);
    ASSERT_FALSE(over.computed());
    const ExactStability::Unfactored& b = over.unfactored;
    if (b.patch_nodes == 0) continue;
    ++patches;
    const auto verdict = [&](double gamma, double dt) {
      Params q = p;
      q.gamma = gamma;
      q.dt = dt;
      const Model mq = compile_model(spec, q);
      ++claims;
      return exact_stability(mq, x, q).stable;
    };
    if (over.stable) {
      EXPECT_TRUE(verdict(p.gamma, p.dt));
    }
    if (std::isfinite(b.gamma_unstable_from)) {
      EXPECT_FALSE(verdict(b.gamma_unstable_from * (1 + 1e-8), p.dt));
    }
    if (std::isfinite(b.dt_unstable_from)) {
      EXPECT_FALSE(verdict(p.gamma, b.dt_unstable_from * (1 + 1e-8)));
    }
    if (std::isfinite(b.gamma_stable_hi) && b.gamma_stable_hi > 0) {
      EXPECT_TRUE(verdict(b.gamma_stable_hi * (1 - 1e-8), p.dt));
    }
    if (std::isfinite(b.dt_stable_up_to) && b.dt_stable_up_to > 0) {
      EXPECT_TRUE(verdict(p.gamma, b.dt_stable_up_to * (1 - 1e-8)));
    }
  }
  std::printf("random states: %d with a patch, %d claims checked\n", patches, claims);
  EXPECT_GE(patches, 2);
}

TEST(IndexPatch, OverTheBudgetAStiffInclusionsPatchNarrowsLambdaMax) {
  // A stiff inclusion (the springs at one node in the block's middle 6x stiffer, as a badly
  // shaped small element makes) puts A's own top there: a patch around it brackets lambda_max
  // where the splitting's bound lay far above.
  const int nx = 15, ny = 9, nz = 13, centre = (7 * ny + 4) * nz + 6;
  ModelSpec spec = lumped_block(nx, ny, nz);
  for (Spring& sp : spec.springs)
    if (sp.i == centre || sp.j == centre) sp.kappa_scale *= 6;
  Params p = tissue_params();
  const Model model = compile_model(spec, p);
  const ExactStability exact = exact_stability(model, model.spec().rest, p);
  ExactOptions none;
  none.max_factor_flops = 1;
  ExactOptions budget;
  budget.max_factor_flops = 0.99 * exact_stability(model, model.spec().rest, p, none).factor_flops;
  const ExactStability over = exact_stability(model, model.spec().rest, p, budget);
  ASSERT_FALSE(over.computed());
  const ExactStability::Unfactored& b = over.unfactored;
  EXPECT_GT(b.lambda_patch_nodes, 0);
  std::printf(
      "lambda_max in [%.12g, %.12g] (a patch of %d nodes; Gershgorin %.9g), "
      "factorised [%.12g, %.12g]\n",
      b.lambda_max_lo, b.lambda_max_hi, b.lambda_patch_nodes, b.gershgorin, exact.lambda_max_lo,
      exact.spectrum.lambda_max);
  EXPECT_LE(b.lambda_max_lo, exact.spectrum.lambda_max);
  EXPECT_GE(b.lambda_max_hi, exact.lambda_max_lo);
  EXPECT_LT(b.lambda_max_hi - b.lambda_max_lo, 1e-8 * b.lambda_max_lo);
  EXPECT_LT(b.lambda_max_hi, 0.8 * b.gershgorin);
  // Without the budget for a patch: the splitting's bound and a Lanczos quotient.
  const ExactStability::Unfactored& n = exact_stability(model, model.spec().rest, p, none).unfactored;
  EXPECT_EQ(n.lambda_patch_nodes, 0);
  EXPECT_GT(n.lambda_max_hi, 1.1 * exact.spectrum.lambda_max);
}

}  // namespace
}  // namespace dampbound
