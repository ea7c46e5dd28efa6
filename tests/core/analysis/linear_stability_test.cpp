#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// Tests of core/linear_stability*: the tangent stiffness against finite differences, Lanczos
// against a dense solver, the closed forms of SPEC 7, the non-uniform symmetric criterion
// against the dense amplification matrix, and runs just inside / outside the predicted limits.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/analysis/criteria.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/linear_stability_modes.hpp"
#include "core/analysis/perturbation_growth.hpp"
#include "core/io/scene_file.hpp"
#include "core/physics/detail/spring_block.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/forces.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/grid_models.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

using test::deformed;
using test::grid_model;

std::string source_path(const std::string& rel) { return std::string(DAMPBOUND_SOURCE_DIR) + "/" + rel; }

/// A small non-uniform grid: the first rows heavier and stiffer (like stiff-region.toml).
Model nonuniform_grid(int nx, int nz, const Params& p) {
  GridSpec g;
  g.nx = nx;
  g.nz = nz;
  g.spacing = 0.57;
  ModelSpec m = make_grid(g);
  for (int i = 0; i < 2 * nz; ++i) m.mass_scale[static_cast<size_t>(i)] = 4, m.anchor_scale[static_cast<size_t>(i)] = 10;
  for (Spring& s : m.springs)
    if (s.i < 2 * nz && s.j < 2 * nz) s.kappa_scale = 10;
  return compile_model(std::move(m), p);
}

Eigen::VectorXd dense_spectrum(const SparseMatrix& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(A), Eigen::EigenvaluesOnly};
  return es.eigenvalues();
}

double dense_rho(Integrator in, const SparseMatrix& Kw, const Eigen::VectorXd& rate, double h) {
  return amplification_matrix_dense(in, Kw, rate, h).eigenvalues().cwiseAbs().maxCoeff();
}

TEST(PsdFloor, IsTheAnchorRateWhenNoSpringIsCompressed) {
  Params p;
  p.m = 0.002;
  p.kappa = 0.05;
  const Model m = nonuniform_grid(6, 6, p);  // heavier, stiffer-anchored first rows
  double expected = 1e300;
  for (size_t i = 0; i < m.spec().rest.size(); ++i)
    if (!m.spec().fixed[i]) expected = std::min(expected, m.anchor_kappa[i] / m.mass[i]);
  // At rest (lengths equal to rest lengths up to rounding) and stretched by 10%.
  std::vector<Vec3> stretched = m.spec().rest;
  for (Vec3& x : stretched) x *= 1.1;
  for (const std::vector<Vec3>* x : std::vector<const std::vector<Vec3>*>{&m.spec().rest, &stretched}) {
    const std::optional<double> floor = psd_floor(m, *x);
    ASSERT_TRUE(floor.has_value());
    EXPECT_NEAR(*floor, expected, 1e-12 * expected);
    EXPECT_LE(*floor, expected);
    const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, *x));
    EXPECT_GE(dense_spectrum(A).minCoeff(), *floor - 1e-12 * expected);
  }
}

TEST(PsdFloor, NoneWithACompressedSpringUnlessClamped) {
  Params p;
  p.m = 0.002;
  p.kappa = 0.05;
  const Model m = grid_model(6, 6, p);
  std::vector<Vec3> squeezed = m.spec().rest;
  for (Vec3& x : squeezed) x *= 0.9;  // every spring 10% short
  EXPECT_FALSE(psd_floor(m, squeezed).has_value());
  // Clamped, the compressed springs keep only kappa d d^T >= 0: the floor holds again.
  const std::optional<double> clamped = psd_floor(m, squeezed, true);
  ASSERT_TRUE(clamped.has_value());
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, squeezed, true));
  EXPECT_GE(dense_spectrum(A).minCoeff(), *clamped - 1e-12);
  // No free node: nothing to bound.
  ModelSpec all_fixed = make_grid(GridSpec{3, 3, 0.57, true, true});
  for (auto& f : all_fixed.fixed) f = 1;
  const Model fixed = compile_model(std::move(all_fixed), p);
  EXPECT_FALSE(psd_floor(fixed, fixed.spec().rest).has_value());
}

TEST(SplittingCeilings, BoundEveryEigenvalueAndTheIndexOnDeformedMeshes) {
  // K <= blockdiag(D_i) (splitting_ceilings): max_i ceiling_i bounds lambda_max of M^-1 K, and
  // max_i (h^2 ceiling_i + 2 h c_i) SPEC 7's index, at rest, stretched and with springs
  // compressed; on the 3-D tissue cap (rim fixed) and a heavier, stiffer-anchored grid.
  Params p;
  p.m = 0.002;
  p.kappa = 0.05;
  const SceneSpec cap = load_scene(source_path("scenes/tissue-cap.toml"));
  for (const Model& m : {nonuniform_grid(6, 6, p), compile_model(cap.model, cap.params)}) {
    std::vector<Vec3> stretched = m.spec().rest;
    for (Vec3& x : stretched) x *= 1.1;
    for (const auto& x : {m.spec().rest, stretched, deformed(m, 0.2)}) {
      const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, x));
      std::vector<double> ceiling;
      splitting_ceilings(m, x, ceiling);
      ASSERT_EQ(ceiling.size(), m.spec().rest.size());
      double top = 0;
      for (size_t i = 0; i < ceiling.size(); ++i) {
        if (m.spec().fixed[i]) {
          EXPECT_EQ(ceiling[i], 0.0);
        }
        top = std::max(top, ceiling[i]);
      }
      const Eigen::VectorXd ev = dense_spectrum(A);
      EXPECT_GE(top, ev.maxCoeff());
      // The index matrix with damping rates varying over the nodes.
      const double h = 0.05;
      Eigen::VectorXd rates(A.rows());
      double index_bound = 0;
      for (size_t i = 0, b = 0; i < m.spec().rest.size(); ++i) {
        if (m.spec().fixed[i]) continue;
        const double c = 0.5 + static_cast<double>(i % 7);
        rates.segment<3>(3 * static_cast<Eigen::Index>(b++)).setConstant(c);
        index_bound = std::max(index_bound, h * h * ceiling[i] + 2 * h * c);
      }
      SparseMatrix S = (h * h) * A;
      S.diagonal() += 2 * h * rates;
      EXPECT_GE(index_bound, dense_spectrum(S).maxCoeff());
    }
  }
  // On the cap at rest it is far below Gershgorin's bound (719.6 against 956.6, lambda_max
  // 370.7: docs/criteria.md).
  const Model m = compile_model(cap.model, cap.params);
  std::vector<double> ceiling;
  splitting_ceilings(m, m.spec().rest, ceiling);
  const double gershgorin = gershgorin_bounds(mass_weighted(m, tangent_stiffness(m, m.spec().rest))).hi;
  EXPECT_LT(*std::max_element(ceiling.begin(), ceiling.end()), 0.8 * gershgorin);
}

TEST(LinearStability, LanczosMatchesDenseOnGrids) {
  Params p;
  p.m = 0.002;
  p.kappa = 0.05;
  for (int n : {4, 10}) {
    const Model m = grid_model(n, n, p);
    for (const auto& x : {m.spec().rest, deformed(m, 0.1)}) {
      const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, x));
      const Eigen::VectorXd ev = dense_spectrum(A);
      EXPECT_NEAR(max_stiffness_eigenvalue(m, x), ev.maxCoeff(), 1e-9 * ev.maxCoeff()) << n;
      EXPECT_NEAR(stiffness_spectrum(m, x).lambda_min, ev.minCoeff(), 1e-8 * ev.maxCoeff()) << n;
    }
  }
}

TEST(LinearStability, TwoNodeClosedForm) {
  Params p;
  p.m = 0.003;
  p.kappa = 0.2;
  p.dt = 0.05;
  const Model m = two_node_system(p);
  const double lambda = max_stiffness_eigenvalue(m, m.spec().rest);
  EXPECT_NEAR(lambda, p.kappa / p.m, 1e-12 * lambda);
  const LinearLimits l = linear_limits(lambda, p.m, p.dt);
  EXPECT_NEAR(l.gamma_max, 2 * p.m / p.dt - p.kappa * p.dt / 2, 1e-12);
  EXPECT_NEAR(l.dt_max_undamped, 2 * std::sqrt(p.m / p.kappa), 1e-12);
  // dt_max(c) is the root of lambda dt^2 + 2 c dt = 4.
  const double c = 3.0, t = semi_implicit_dt_max(lambda, c);
  EXPECT_NEAR(lambda * t * t + 2 * c * t, 4.0, 1e-12);
}

TEST(LinearStability, PaperPlaneLambdaMax) {
  const SceneSpec s = load_scene(source_path("scenes/paper-plane.toml"));
  Params p = s.params;  // m = kappa = 0.001
  const Model m = compile_model(s.model, p);
  const StiffnessSpectrum sp = stiffness_spectrum(m, m.spec().rest);
  EXPECT_NEAR(sp.lambda_max, 7.8123249218733, 1e-9);  // measured; docs/criteria.md
  EXPECT_NEAR(sp.lambda_min, 1.0, 1e-9);              // the anchors: kappa/m
  p.kappa = 0.1;  // lambda scales with kappa/m (SPEC 6)
  p.m = 0.005;
  const Model m2 = compile_model(s.model, p);
  EXPECT_NEAR(max_stiffness_eigenvalue(m2, m2.spec().rest), 20 * sp.lambda_max, 1e-8 * 20 * sp.lambda_max);
}

TEST(LinearStability, SymmetricIndexIsExactForNonUniformDamping) {
  Params p;
  p.m = 0.001;
  p.kappa = 0.004;
  p.dt = 0.1;
  const Model m = nonuniform_grid(4, 4, p);
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, m.spec().rest));
  // gamma_i = gamma (gamma_scale 1) on masses 1x and 4x: rates differ by 4.
  for (double gamma : {0.001, 0.004, 0.01, 0.015, 0.02, 0.03}) {
    const std::vector<double> g(m.spec().rest.size(), gamma);
    const double index = semi_implicit_stability_index(m, A, g, p.dt);
    const double rho = dense_rho(Integrator::semi_implicit_euler, A, damping_rates(m, g), p.dt);
    EXPECT_EQ(index < 4, rho <= 1 + 1e-12) << "gamma " << gamma << " index " << index << " rho " << rho;
  }
  p.gamma = 0.005;
  const Model m5 = compile_model(m, p);
  const ExactStability e = exact_stability(m5, m5.spec().rest, p);
  ASSERT_EQ(e.method, ExactMethod::symmetric_index);
  auto rho_at = [&](double gamma, double dt) {
    const std::vector<double> g(m.spec().rest.size(), gamma);
    return dense_rho(Integrator::semi_implicit_euler, A, damping_rates(m, g), dt);
  };
  EXPECT_LE(rho_at(0.999 * e.gamma_hi, p.dt), 1.0);
  EXPECT_GT(rho_at(1.001 * e.gamma_hi, p.dt), 1.0);
  EXPECT_LE(rho_at(p.gamma, 0.999 * e.dt_max), 1.0);
  EXPECT_GT(rho_at(p.gamma, 1.001 * e.dt_max), 1.0);
}

TEST(LinearStability, PerModeAnalysisMatchesTheWholeOperator) {
  Params p;
  p.kappa = 0.02;
  p.dt = 0.1;
  const Model m = grid_model(3, 3, p);
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, m.spec().rest));
  const StiffnessSpectrum sp = stiffness_spectrum(m, m.spec().rest);
  for (Integrator in : {Integrator::semi_implicit_euler, Integrator::forward_euler, Integrator::verlet,
                        Integrator::rk4, Integrator::implicit_euler})
    for (double c : {0.0, 0.7, 3.0, 15.0}) {
      const double dense = dense_rho(in, A, Eigen::VectorXd::Constant(A.rows(), c), p.dt);
      const double modes = spectrum_spectral_radius(in, sp, c, p.dt);
      // The ends of [lambda_min, lambda_max] are exact for the two Euler steps; for the
      // others the sampled interval bounds the discrete spectrum from above.
      if (in == Integrator::semi_implicit_euler || in == Integrator::forward_euler)
        EXPECT_NEAR(modes, dense, 1e-7) << to_string(in) << " c " << c;
      else
        EXPECT_GE(modes, dense - 1e-7) << to_string(in) << " c " << c;
    }
}

TEST(LinearStability, ArnoldiMatchesDenseOnASmallNonUniformMesh) {
  Params p;
  p.kappa = 0.01;
  p.gamma = 0.02;
  p.dt = 0.2;
  const Model m = nonuniform_grid(5, 5, p);  // 150 dofs: Arnoldi, not the dense shortcut
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, m.spec().rest));
  const Eigen::VectorXd rate = damping_rates(m, m.gamma);
  for (Integrator in : {Integrator::forward_euler, Integrator::verlet, Integrator::rk4}) {
    const SpectralRadius s = amplification_spectral_radius(in, A, rate, p.dt);
    EXPECT_NEAR(s.rho, dense_rho(in, A, rate, p.dt), s.converged ? 1e-6 : 1e-3) << to_string(in);
  }
}

/// Steps enough for growth by 1e5 at rho, at most 3000.
int steps_for(double rho) { return rho > 1 ? static_cast<int>(std::min(3000.0, std::ceil(std::log(1e5) / std::log(rho)))) : 300; }

TEST(LinearStability, TwoNodeRunsDecayInsideAndGrowOutside) {
  Params p;
  p.dt = 0.05;
  const Model base = two_node_system(p);
  const double gamma_max = linear_limits(p.kappa / p.m, p.m, p.dt).gamma_max;
  for (double f : {0.98, 1.02}) {
    Params q = p;
    q.gamma = f * gamma_max;
    const Model m = compile_model(base, q);
    const double rho = spectrum_spectral_radius(q.integrator, {p.kappa / p.m, p.kappa / p.m}, q.gamma / q.m, q.dt);
    const double growth = perturbation_growth(m, q, steps_for(rho));
    if (f < 1) EXPECT_LT(growth, 1.0) << growth;
    else EXPECT_GT(growth, 10.0) << growth;
  }
}

TEST(LinearStability, StiffRegionRunsDecayInsideAndGrowOutside) {
  const SceneSpec s = load_scene(source_path("scenes/stiff-region.toml"));
  const Params p = s.params;  // m = kappa = 0.001, gamma = 0.02, dt = 0.05
  const Model m = compile_model(s.model, p);
  const ExactStability e = exact_stability(m, m.spec().rest, p, {false});
  ASSERT_EQ(e.method, ExactMethod::symmetric_index);
  EXPECT_FALSE(e.uniform_rate);
  EXPECT_NEAR(e.gamma_hi, 0.0398054, 1e-6);  // measured; docs/criteria.md
  EXPECT_NEAR(e.dt_max, 0.0981261, 1e-6);
  for (double f : {0.95, 1.05}) {
    Params q = p;
    q.gamma = f * e.gamma_hi;
    Model mq = compile_model(s.model, q);
    const double g1 = perturbation_growth(mq, q, f < 1 ? 300 : 120);
    q = p;
    q.dt = f * e.dt_max;
    const double g2 = perturbation_growth(m, q, f < 1 ? 300 : 120);
    if (f < 1) {
      EXPECT_LT(g1, 1.0);
      EXPECT_LT(g2, 1.0);
    } else {
      EXPECT_GT(g1, 10.0);
      EXPECT_GT(g2, 10.0);
    }
  }
}

}  // namespace
}  // namespace dampbound

