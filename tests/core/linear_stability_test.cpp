#include "core/linear_stability_gcc.hpp"  // first: silences GCC 12 false positives
// Tests of core/linear_stability: tangent stiffness, Lanczos against a dense solver, the
// exact limits of the paper's step.
#include "core/linear_stability.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>

#include "core/scene.hpp"

namespace dampbound {
namespace {

Model grid_model(int nx, int nz, const Params& p) {
  GridSpec g;
  g.nx = nx;
  g.nz = nz;
  g.spacing = 0.57;
  Model m = make_grid(g);
  set_params(m, p);
  return m;
}

double dense_max(const SparseMatrix& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(A)};
  return es.eigenvalues().maxCoeff();
}

TEST(LinearStability, LanczosMatchesDenseOnGrid) {
  Params p;
  Model m = grid_model(4, 4, p);
  const SparseMatrix A = mass_weighted(m, tangent_stiffness(m, m.rest));
  const double dense = dense_max(A);
  EXPECT_NEAR(max_stiffness_eigenvalue(m, m.rest), dense, 1e-10 * dense);
}

TEST(LinearStability, PaperPlaneTiming) {
  const SceneSpec s = load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/paper-plane.toml");
  Params p = s.params;
  const Model m = make_model(s, p);
  const auto t0 = std::chrono::steady_clock::now();
  const StiffnessSpectrum sp = stiffness_spectrum(m, m.rest);
  const auto t1 = std::chrono::steady_clock::now();
  std::printf("lambda_min %.17g lambda_max %.17g  %.3f s\n", sp.lambda_min, sp.lambda_max,
              std::chrono::duration<double>(t1 - t0).count());
}

}  // namespace
}  // namespace dampbound
