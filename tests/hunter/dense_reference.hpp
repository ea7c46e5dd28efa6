#pragma once
// The hunter's independent reference: the linearised step of each integrator at rest, built
// as a dense matrix from the spec and the parameters alone (none of dampbound's stiffness,
// damping or mode code), and its spectral radius by a dense eigensolver. Small meshes only.
#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "dampbound/physics/model.hpp"
#include "dampbound/physics/params.hpp"

namespace dampbound::hunt {

/// K and C over the free dofs at rest (every spring at its rest length, so a spring's block is
/// kappa d d^T; an anchor's kappa_a I), and the masses per free dof. C = diag(gamma_i) +
/// alpha M + beta K + the dashpots (kd d d^T per spring, kd_a I per anchor): SPEC 10.
/// Every number is in the model's own units, mass p.m, stiffness p.kappa, time T =
/// sqrt(p.m / p.kappa) (damping then in sqrt(p.m p.kappa)): the step's matrix in those units is
/// similar to the one in cm and s (the velocity rescaled by T), so its eigenvalues are the
/// same, and its entries stay near 1 at every magnitude the hunter draws (a dense eigensolver
/// on entries 1e-12 beside 1e9 loses the digits that decide |z| <= 1).
struct DenseSystem {
  Eigen::MatrixXd K, C, Cnodal;  ///< Cnodal: diag(gamma_i), the part Verlet treats implicitly
  Eigen::VectorXd mass;
  double time_unit = 1;  ///< T (s): dense_step takes h / T
};

inline DenseSystem dense_system(const ModelSpec& spec, const Params& p) {
  const size_t n = spec.rest.size();
  std::vector<int> dof(n, -1);
  int free = 0;
  for (size_t i = 0; i < n; ++i)
    if (!spec.fixed[i]) dof[i] = 3 * free++;
  DenseSystem s;
  const double mu = p.m, ku = p.kappa, cu = std::sqrt(p.m * p.kappa);
  s.time_unit = std::sqrt(p.m) / std::sqrt(p.kappa);
  const Eigen::Index N = 3 * free;
  s.K = Eigen::MatrixXd::Zero(N, N);
  Eigen::MatrixXd Cd = Eigen::MatrixXd::Zero(N, N);  // dashpots
  s.Cnodal = Eigen::MatrixXd::Zero(N, N);
  s.mass.resize(N);
  const auto add = [&](Eigen::MatrixXd& X, size_t i, size_t j, const Eigen::Matrix3d& B) {
    // [B, -B; -B, B] on (i, j); rows and columns of fixed nodes dropped.
    const int a = dof[i], b = dof[j];
    if (a >= 0) X.block<3, 3>(a, a) += B;
    if (b >= 0) X.block<3, 3>(b, b) += B;
    if (a >= 0 && b >= 0) {
      X.block<3, 3>(a, b) -= B;
      X.block<3, 3>(b, a) -= B;
    }
  };
  for (const Spring& sp : spec.springs) {
    const Vec3 d = (spec.rest[size_t(sp.j)] - spec.rest[size_t(sp.i)]).normalized();
    const Eigen::Matrix3d P = d * d.transpose();
    add(s.K, size_t(sp.i), size_t(sp.j), (p.kappa / ku) * sp.kappa_scale * P);
    add(Cd, size_t(sp.i), size_t(sp.j), (p.kd / cu) * sp.kd_scale * P);
  }
  for (size_t i = 0; i < n; ++i) {
    if (dof[i] < 0) continue;
    const double m = (p.m / mu) * spec.mass_scale[i];
    const double kd_a =
        spec.anchor_scale[i] > 0
            ? (p.kd / cu) * (spec.anchor_kd_scale.empty() ? 1.0 : spec.anchor_kd_scale[i])
            : 0.0;
    for (int r = 0; r < 3; ++r) {
      const int k = dof[i] + r;
      s.mass(k) = m;
      s.K(k, k) += (p.kappa / ku) * spec.anchor_scale[i];
      Cd(k, k) += kd_a;
      s.Cnodal(k, k) = (p.gamma / cu) * spec.gamma_scale[i];
    }
  }
  // alpha M in units of cu: alpha (1/s) T; beta K: beta (s) / T.
  s.C = s.Cnodal + Cd + (p.rayleigh_mass * s.time_unit) * Eigen::MatrixXd(s.mass.asDiagonal()) +
        (p.rayleigh_stiffness / s.time_unit) * s.K;
  return s;
}

/// One step h (in units of T) of the integrator on M y'' = -K y - C y' (integrate.cpp's
/// arithmetic, linearised), as the 2N x 2N matrix acting on (y, v).
inline Eigen::MatrixXd dense_step(const DenseSystem& s, Integrator integrator, double h) {
  const Eigen::Index N = s.mass.size();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(N, N);
  const Eigen::MatrixXd Minv = s.mass.cwiseInverse().asDiagonal();
  Eigen::MatrixXd G(2 * N, 2 * N);
  const Eigen::MatrixXd Ay = -Minv * s.K, Av = -Minv * s.C;  // a = Ay y + Av v
  switch (integrator) {
    case Integrator::semi_implicit_euler: {  // v' = v + h a; y' = y + h v'
      const Eigen::MatrixXd vy = h * Ay, vv = I + h * Av;
      G << I + h * vy, h * vv, vy, vv;
      return G;
    }
    case Integrator::forward_euler:  // y' = y + h v; v' = v + h a
      G << I, h * I, h * Ay, I + h * Av;
      return G;
    case Integrator::verlet: {
      // v_h = v + h/2 a(y, v); y' = y + h v_h;
      // v' = (v_h + h/2 M^-1 (-K y' - (C - Cnodal) v_h)) / (1 + h gamma_i / (2 m_i))
      const Eigen::MatrixXd hy = (h / 2) * Ay, hv = I + (h / 2) * Av;  // v_h
      const Eigen::MatrixXd yy = I + h * hy, yv = h * hv;              // y'
      const Eigen::MatrixXd D =
          (I + (h / 2) * Minv * s.Cnodal).inverse();
      const Eigen::MatrixXd Cs = s.C - s.Cnodal;
      const Eigen::MatrixXd kick = I - (h / 2) * Minv * Cs;
      const Eigen::MatrixXd vy = D * (kick * hy - (h / 2) * Minv * s.K * yy);
      const Eigen::MatrixXd vv = D * (kick * hv - (h / 2) * Minv * s.K * yv);
      G << yy, yv, vy, vv;
      return G;
    }
    case Integrator::rk4: {
      Eigen::MatrixXd J(2 * N, 2 * N);
      J << Eigen::MatrixXd::Zero(N, N), I, Ay, Av;
      const Eigen::MatrixXd hJ = h * J;
      Eigen::MatrixXd term = Eigen::MatrixXd::Identity(2 * N, 2 * N);
      G = term;
      for (int k = 1; k <= 4; ++k) {
        term = term * hJ / k;
        G += term;
      }
      return G;
    }
    case Integrator::implicit_euler: {  // (M + hC + h^2 K) v' = M v - h K y; y' = y + h v'
      const Eigen::MatrixXd M = s.mass.asDiagonal();
      const Eigen::MatrixXd S = (M + h * s.C + h * h * s.K).inverse();
      const Eigen::MatrixXd vy = -h * S * s.K, vv = S * M;
      G << I + h * vy, h * vv, vy, vv;
      return G;
    }
  }
  return G;
}

/// The spectral radius of one step (dense eigenvalues).
inline double dense_radius(const DenseSystem& s, Integrator integrator, double h) {
  if (s.mass.size() == 0) return 0;
  const Eigen::MatrixXd G = dense_step(s, integrator, h / s.time_unit);
  if (!G.allFinite()) return std::numeric_limits<double>::infinity();
  return G.eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace dampbound::hunt
