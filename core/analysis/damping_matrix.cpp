#include "core/analysis/damping_matrix.hpp"

#include <cmath>

namespace dampbound {

SparseMatrix spring_damping_matrix(const Model& model, const std::vector<Vec3>& x,
                                   bool clamp_compression) {
  int nfree = 0;
  const std::vector<int> block = free_blocks(model, &nfree);
  std::vector<Eigen::Triplet<double>> t;
  const double alpha = model.rayleigh_mass, beta = model.rayleigh_stiffness;
  for (size_t i = 0; i < model.rest.size(); ++i) {
    const int b = block[i];
    if (b < 0) continue;
    const double diag = alpha * model.mass[i] + beta * model.anchor_kappa[i] + model.anchor_kd[i];
    if (diag != 0)
      for (int r = 0; r < 3; ++r) t.emplace_back(3 * b + r, 3 * b + r, diag);
  }
  for (size_t k = 0; k < model.springs.size(); ++k) {
    const Spring& s = model.springs[k];
    const Vec3 delta = x[static_cast<size_t>(s.j)] - x[static_cast<size_t>(s.i)];
    const double l = delta.norm();
    if (!(l > 0)) continue;
    const Vec3 d = delta / l;
    const double ratio = s.rest_length / l;
    double tension = 1.0 - ratio;
    if (clamp_compression) tension = std::max(0.0, tension);
    const double kappa = model.spring_kappa[k], kd = model.spring_kd[k];
    // beta B + kd P = (beta kappa ratio + kd) d d^T + beta kappa tension I
    const Eigen::Matrix3d E = (beta * kappa * ratio + kd) * (d * d.transpose()) +
                              (beta * kappa * tension) * Eigen::Matrix3d::Identity();
    const int bi = block[static_cast<size_t>(s.i)], bj = block[static_cast<size_t>(s.j)];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const double e = E(r, c);
        if (e == 0) continue;
        if (bi >= 0) t.emplace_back(3 * bi + r, 3 * bi + c, e);
        if (bj >= 0) t.emplace_back(3 * bj + r, 3 * bj + c, e);
        if (bi >= 0 && bj >= 0) {
          t.emplace_back(3 * bi + r, 3 * bj + c, -e);
          t.emplace_back(3 * bj + r, 3 * bi + c, -e);
        }
      }
  }
  SparseMatrix C(3 * nfree, 3 * nfree);
  C.setFromTriplets(t.begin(), t.end());
  return C;
}

SparseMatrix weighted_damping(const Model& model, const std::vector<Vec3>& x,
                              const std::vector<double>& gamma) {
  SparseMatrix C = spring_damping_matrix(model, x);
  int nfree = 0;
  const std::vector<int> block = free_blocks(model, &nfree);
  Eigen::VectorXd w(3 * nfree);
  std::vector<Eigen::Triplet<double>> g;
  for (size_t i = 0; i < model.rest.size(); ++i) {
    const int b = block[i];
    if (b < 0) continue;
    for (int r = 0; r < 3; ++r) {
      w(3 * b + r) = 1.0 / std::sqrt(model.mass[i]);
      if (gamma[i] != 0) g.emplace_back(3 * b + r, 3 * b + r, gamma[i]);
    }
  }
  SparseMatrix G(3 * nfree, 3 * nfree);
  G.setFromTriplets(g.begin(), g.end());
  C += G;
  return w.asDiagonal() * C * w.asDiagonal();
}

}  // namespace dampbound
