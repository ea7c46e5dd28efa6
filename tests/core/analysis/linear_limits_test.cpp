// linear_limits on a user's matrices (core/analysis/linear_limits.hpp): the same numbers as
// the scene's own analysis (exact_stability, SPEC 9's safe bound) for the scene's K.
#include "core/analysis/linear_limits.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/analysis/damping_limits.hpp"
#include "core/io/scene_file.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/stiffness.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

void expect_rel(double a, double b, double tol, const char* what) {
  EXPECT_LE(std::abs(a - b), tol * std::max(std::abs(a), std::abs(b))) << what << ": " << a
                                                                       << " vs " << b;
}

/// The scene's model, its K at rest and the two analyses side by side.
void compare(const Model& model, const Params& p) {
  const std::vector<Vec3>& x = model.spec().rest;
  const SparseMatrix K = tangent_stiffness(model, x);
  MatrixModel mm;
  mm.K = &K;
  mm.mass = model.mass;
  mm.gamma = model.gamma;  // gamma_i = gamma * gamma_scale_i
  mm.dt = p.dt;
  const MatrixLimits got = linear_limits(mm);
  const ExactStability want = exact_stability(model, x, p);
  EXPECT_EQ(got.exact.method, want.method);
  expect_rel(got.lambda_max_hi, want.spectrum.lambda_max, 1e-12, "lambda_max (certified)");
  expect_rel(got.lambda_max_lo, want.lambda_max_lo, 1e-12, "lambda_max (Rayleigh)");
  expect_rel(got.dt_max, want.dt_max, 1e-9, "dt_max");
  // The scene's gamma_hi is of the user's gamma; here of g in gamma_i = g gamma_i / gamma_ref.
  expect_rel(got.gamma_max * p.gamma / got.gamma_ref, want.gamma_hi, 1e-9, "gamma_max");
  EXPECT_EQ(got.stable, want.stable);
  std::vector<double> row_sum;
  safe_row_sums(model, x, row_sum);
  for (size_t i = 0; i < model.mass.size(); ++i) {
    expect_rel(got.row_sum[i], row_sum[i], 1e-12, "R_i");
    expect_rel(got.gamma_safe[i], safe_gamma(model.mass[i], p.dt, row_sum[i]), 1e-12,
               "gamma_safe_i");
    expect_rel(got.dt_safe[i], safe_dt(model.mass[i], model.gamma[i], row_sum[i]), 1e-12,
               "dt_safe_i");
  }
}

TEST(LinearLimits, SameNumbersAsTheScenesAnalysis) {
  const SceneSpec scene = load_scene(test::source_path("scenes/paper-plane.toml"));
  Params p = scene.params;
  p.dt = 0.3;  // well inside dt_max, a non-trivial gamma interval
  compare(compile_model(scene.model, p), p);
}

TEST(LinearLimits, PerNodeGammaTakesTheSymmetricIndex) {
  SceneSpec scene = paper_plane_scene(12);
  for (size_t i = 0; i < scene.model.gamma_scale.size(); ++i)
    scene.model.gamma_scale[i] = 1.0 + double(i % 5) / 4;  // up to 2, the largest
  Params p = scene.params;
  p.dt = 0.3;
  const Model model = compile_model(scene.model, p);
  compare(model, p);
}

TEST(LinearLimits, BadInputNamesTheArgument) {
  const SparseMatrix K = tangent_stiffness(compile_model(paper_plane_scene(3).model, Params{}),
                                           paper_plane_scene(3).model.rest);
  MatrixModel mm;
  mm.K = &K;
  mm.mass.assign(9, 0.001);
  mm.gamma = {0.002};
  mm.dt = 0.05;
  EXPECT_EQ(test::input_error([&] { linear_limits(mm); }), "");
  mm.mass.assign(8, 0.001);
  EXPECT_EQ(test::input_error([&] { linear_limits(mm); }).substr(0, 20), "K: must be 3N x 3N f");
  mm.mass.assign(9, 0.001);
  mm.mass[4] = 0;
  EXPECT_EQ(test::input_error([&] { linear_limits(mm); }).substr(0, 24), "mass: node 4 has mass 0;");
  mm.mass[4] = 0.001;
  SparseMatrix bent = K;
  bent.coeffRef(0, 1) += 1;
  mm.K = &bent;
  EXPECT_EQ(test::input_error([&] { linear_limits(mm); }).substr(0, 20), "K: not symmetric: en");
  mm.K = &K;
  const SparseMatrix small(3, 3);
  mm.C = &small;
  EXPECT_EQ(test::input_error([&] { linear_limits(mm); }).substr(0, 30),
            "C: must be 3N x 3N for the N =");
  mm.C = &bent;
  EXPECT_EQ(test::input_error([&] { linear_limits(mm); }).substr(0, 20), "C: not symmetric: en");
}

// A damping matrix (SPEC 10): a plane with dashpots and Rayleigh damping, its K and C'
// assembled by core and given as matrices, judged as `bounds` judges the scene.
TEST(LinearLimits, ADampingMatrixGivesTheScenesGeneralLimits) {
  const SceneSpec scene = paper_plane_scene(8);
  Params p = scene.params;
  p.kd = 0.002;
  p.rayleigh_mass = 0.01;
  p.rayleigh_stiffness = 0.001;
  const Model model = compile_model(scene.model, p);
  const std::vector<Vec3>& x = model.spec().rest;
  const SparseMatrix K = tangent_stiffness(model, x);
  const SparseMatrix C = spring_damping_matrix(model, x);
  MatrixModel mm;
  mm.K = &K;
  mm.C = &C;
  mm.mass = model.mass;
  mm.gamma = model.gamma;
  mm.dt = p.dt;
  const MatrixLimits got = linear_limits(mm);
  const GeneralLimits want = general_limits(model, x, p);
  ASSERT_FALSE(want.commuting);
  EXPECT_TRUE(got.damping_matrix);
  expect_rel(got.index, want.index, 1e-12, "index");
  expect_rel(got.damping_min, want.damping_min, 1e-9, "lambda_min(C^)");
  expect_rel(got.dt_max, want.dt_max, 1e-9, "dt_max");
  expect_rel(got.gamma_max, want.gamma_max, 1e-9, "gamma_max");
  EXPECT_EQ(got.stable, want.index < 4 && want.damping_min > 0);
  const DampedSafeRows rows(model, x);
  for (size_t i = 0; i < model.mass.size(); ++i) {
    expect_rel(got.gamma_safe[i], rows.gamma_safe(int(i), p.dt), 1e-12, "gamma_safe_i");
    expect_rel(got.dt_safe[i], rows.dt_safe(int(i), model.gamma[i]), 1e-12, "dt_safe_i");
  }
}

}  // namespace
}  // namespace dampbound

namespace dampbound {
namespace {

/// A 2-node, 6-dof model: K = k on x of node 0 and on the x difference, C as given.
SparseMatrix diagonal(const std::vector<double>& d) {
  SparseMatrix X(Eigen::Index(d.size()), Eigen::Index(d.size()));
  for (size_t i = 0; i < d.size(); ++i) X.insert(Eigen::Index(i), Eigen::Index(i)) = d[i];
  X.makeCompressed();
  return X;
}

// linear_limits said stable False and dt_max 0 beside a finite safe dt on a K that is not
// positive semi-definite: no damping bound helps a mode that grows (SPEC 9).
TEST(LinearLimits, AnIndefiniteKGuaranteesNothing) {
  const SparseMatrix K = diagonal({1, 1, 1, 1, 1, -0.5});
  MatrixModel mm;
  mm.K = &K;
  mm.mass = {1, 1};
  mm.gamma = {0.1};
  mm.dt = 0.1;
  const MatrixLimits r = linear_limits(mm);
  EXPECT_FALSE(r.stable);
  EXPECT_EQ(r.dt_max, 0);
  EXPECT_FALSE(r.reason.empty());
  for (double dt : r.dt_safe) EXPECT_EQ(dt, 0) << "no dt is safe";
  for (double g : r.gamma_safe) EXPECT_FALSE(g > 0) << "no gamma is safe";
  const SparseMatrix C = diagonal({0.1, 0.1, 0.1, 0.1, 0.1, 0.1});
  mm.C = &C;
  const MatrixLimits d = linear_limits(mm);
  EXPECT_FALSE(d.stable);
  EXPECT_EQ(d.dt_max, 0);
  for (double dt : d.dt_safe) EXPECT_EQ(dt, 0);
}

// The same with a C that is not positive semi-definite: the index does not decide, so no
// limit and no safe bound is given (NaN), and the verdict is not "stable".
TEST(LinearLimits, AnIndefiniteCDecidesNothing) {
  const SparseMatrix K = diagonal({1, 1, 1, 1, 1, 1});
  const SparseMatrix C = diagonal({0.1, 0.1, 0.1, 0.1, 0.1, -0.05});
  MatrixModel mm;
  mm.K = &K;
  mm.C = &C;
  mm.mass = {1, 1};
  mm.gamma = {0};
  mm.dt = 0.1;
  const MatrixLimits r = linear_limits(mm);
  EXPECT_FALSE(r.stable);
  EXPECT_TRUE(std::isnan(r.dt_max));
  EXPECT_TRUE(std::isnan(r.gamma_max));
  EXPECT_NE(r.reason.find("C is not positive semi-definite"), std::string::npos) << r.reason;
  for (double dt : r.dt_safe) EXPECT_TRUE(std::isnan(dt));
}

}  // namespace
}  // namespace dampbound
