#pragma once
// The paper's step linearised at rest as a dense matrix, for tests that check an analysis
// against it (no index theory): v' = v - dt M^-1 (K x + C v), x' = x + dt v', with
// C = diag(gamma_i) + alpha M + beta K + dashpots (SPEC 10), over the free nodes.
#include <Eigen/Dense>

#include "dampbound/physics/stiffness.hpp"

namespace dampbound::test {

/// Spectral radius of the step's amplification matrix at rest with the model's damping.
inline double dense_step_radius(const Model& model, double dt) {
  const std::vector<Vec3>& x = model.spec().rest;
  const Eigen::MatrixXd K = Eigen::MatrixXd(tangent_stiffness(model, x));
  Eigen::MatrixXd C = Eigen::MatrixXd(spring_damping_matrix(model, x));
  const long n = K.rows();
  Eigen::VectorXd minv(n);
  for (size_t i = 0, b = 0; i < model.spec().rest.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    for (long r = 0; r < 3; ++r) {
      const long d = static_cast<long>(3 * b) + r;
      minv(d) = 1 / model.mass[i];
      C(d, d) += model.gamma[i];
    }
    ++b;
  }
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd MK = minv.asDiagonal() * K, MC = minv.asDiagonal() * C;
  Eigen::MatrixXd T(2 * n, 2 * n);
  T << I - dt * dt * MK, dt * (I - dt * MC), -dt * MK, I - dt * MC;
  return T.eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace dampbound::test
