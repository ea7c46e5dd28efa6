#pragma once
// Linear stability of every integrator (SPEC 7): one step of each integrator applied
// to the linearised system y'' = -A y - C y' (A = M^-1/2 K M^-1/2, C = M^-1 Gamma, the
// damping held over the step as in integrate.cpp), as a per-mode 2x2 matrix (lambda, c) and
// as a matrix-free 2n x 2n amplification operator over a whole mesh.
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/params.hpp"

namespace dampbound {

/// The 2x2 amplification matrix of one step of `integrator` on the mode y'' = -lambda y - c y'
/// with step h, acting on (y, y'). Columns are the step applied to (1, 0) and (0, 1):
///   semi-implicit Euler  [[1 - h^2 lambda, h (1 - c h)], [-h lambda, 1 - c h]]   (SPEC 7)
///   forward Euler        [[1, h], [-h lambda, 1 - c h]]
///   velocity Verlet      half kick (explicit damping), drift, half kick (damping implicit)
///   RK4                  sum_k (h J)^k / k!, k = 0..4, J = [[0, 1], [-lambda, -c]]
///   implicit Euler       v' = (v - h lambda y)/(1 + h c + h^2 lambda), y' = y + h v'
Eigen::Matrix2d mode_amplification(Integrator integrator, double lambda, double c, double h);

/// Spectral radius of mode_amplification (max |z| of its two eigenvalues).
double mode_spectral_radius(Integrator integrator, double lambda, double c, double h);

/// max over lambda in [lambda_min, lambda_max] of mode_spectral_radius: the spectral radius
/// of the whole step when c = gamma_i/m_i is uniform (the modes of M^-1 K decouple). Both ends
/// and 63 points between are taken; for semi-implicit and forward Euler |z| depends on lambda
/// through a quasi-convex function, so the ends alone are exact (docs/criteria.md).
double spectrum_spectral_radius(Integrator integrator, const StiffnessSpectrum& spectrum,
                                double c, double h);

/// Largest dt with spectrum_spectral_radius < 1 at uniform damping rate c (1/s): closed form
/// for semi-implicit Euler, +infinity for implicit Euler (A-stable), else bracketing and
/// bisection to 1e-12 relative. 0 when no dt > 0 is stable (forward Euler with c = 0).
double uniform_dt_max(Integrator integrator, const StiffnessSpectrum& spectrum, double c);

/// The interval of c (1/s) with spectrum_spectral_radius < 1 at step h; empty when lo >= hi.
/// hi may be +infinity (implicit Euler). Semi-implicit: 0 < c < (4 - lambda_max h^2)/(2h).
struct RateInterval {
  double lo = 0;
  double hi = 0;
  bool empty() const { return !(lo < hi); }
};
RateInterval uniform_rate_interval(Integrator integrator, const StiffnessSpectrum& spectrum,
                                   double h);

/// Forward Euler and velocity Verlet at uniform rate c >= 0 and step h > 0, in closed form:
/// every mode with lambda >= `lambda_from` has spectral radius above 1 + 1e-12 (what
/// uniform_dt_max counts as unstable), proved from the 2x2 step's trace t and determinant d:
///   forward Euler   d = 1 - c h + h^2 lambda, and max |z| >= sqrt|d|;
///   Verlet          t = 2 (1 - h^2 lambda/2) / (1 + c h/2), d = (1 - c h/2)/(1 + c h/2):
///                   z^2 - |t| z + d < 0 at z = 1 + 1e-12 puts a root beyond it.
/// For a mode lambda_0 (e.g. a lower bound of lambda_max) the same condition gives every step
/// h >= `dt_from` (at c) and every rate c <= `rate_below` (at h; -inf: none) as unstable.
/// RK4: `lambda_from` only (>= c^2/4), certified from the quartic |R(z)|^2 in (Im z)^2
/// (docs/criteria.md); dt_from and rate_below NaN. Each is rounded toward the unstable side.
/// NaN for semi-implicit (SPEC 7's index instead) and implicit Euler.
struct ModeInstability {
  double lambda_from = std::numeric_limits<double>::quiet_NaN();
  double dt_from = std::numeric_limits<double>::quiet_NaN();
  double rate_below = std::numeric_limits<double>::quiet_NaN();
};
ModeInstability mode_instability(Integrator integrator, double lambda_0, double c, double h);

/// The stable side, for forward Euler, Verlet and RK4 at uniform rate c >= 0: when every mode
/// lies in [0, lambda_hi] (K >= 0 proved, lambda_max <= lambda_hi), every radius is at most 1
/// iff
///   forward Euler  c h <= 2 and lambda_hi <= c/h  (real roots lie in [1 - c h, 1], complex
///                  ones have |z|^2 = d <= 1);
///   Verlet         lambda_hi h^2 <= 4  (|q| <= 1: |t| <= 1 + d, and |d| <= 1).
/// `stable` at (c, h); every step up to `dt_up_to` is stable at c; every rate in
/// [rate_lo, rate_hi] is stable at h (none when rate_lo > rate_hi). Rounded toward the
/// stable side's inside.
/// RK4 (radius at most 1 + 1e-12, as uniform_dt_max counts it): `stable` at (c, h) by
/// c h <= 2.78529 for the real roots and, for the complex ones, the Bernstein coefficients
/// of |R(z)|^2 - (1 + 1e-12)^2 as a polynomial in (Im z)^2 on [0, h^2 (lambda_hi - c^2/4)];
/// `dt_up_to` the largest step S found for which the same holds at every step in (0, S]
/// (tensor Bernstein coefficients in (h, lambda) on pieces of [0, S]); [rate_lo, rate_hi]
/// the rates around c found the same way at h (in (c, lambda); where c itself is not proved,
/// around the proved one of 31 sample rates nearest to it, which leaves c outside; none,
/// rate_lo > rate_hi, when no sample is proved); false, 0 or shorter where the proofs do
/// not close (near the boundary). docs/criteria.md.
/// `proved` says whether the integrator has this side: false, `stable` false and every
/// number NaN for the semi-implicit step (SPEC 9's safe bound instead) and implicit Euler.
struct ModeStability {
  bool proved = false;
  bool stable = false;
  double dt_up_to = std::numeric_limits<double>::quiet_NaN();
  double rate_lo = std::numeric_limits<double>::quiet_NaN();
  double rate_hi = std::numeric_limits<double>::quiet_NaN();
};
ModeStability mode_stability(Integrator integrator, double lambda_hi, double c, double h);

/// Spectral radius of the 2n x 2n amplification operator of one step of `integrator` on
/// y'' = -A y - C y', A = K_weighted (mass-weighted tangent stiffness over the free nodes),
/// C = diag(rate), rate = gamma_i/m_i per free dof (3 per free node). Matrix-free Arnoldi
/// (Spectra::GenEigsSolver, largest magnitude, on G^4); for implicit Euler each product
/// solves (I + h C + h^2 A) v' = r by conjugate gradients. Lightly damped meshes put n
/// eigenvalues on nearly one circle, where Arnoldi may not converge within its budget
/// (200 restarts); then rho is estimated from the growth of ||G^k u|| over the last 400 of
/// 800 steps and `converged` is false (an estimate from below, good to ~1e-4 in practice).
/// Below 25 rows the dense matrix's eigenvalues are used.
struct SpectralRadius {
  double rho = 0;
  bool converged = true;
};
/// `damping` (optional): SPEC 10's damping besides the nodal one, mass-weighted
/// (M^-1/2 C' M^-1/2 over the free dofs, weighted_damping with zero gamma), applied where
/// integrate.cpp applies it: explicit in every explicit step and in both of Verlet's half
/// kicks, inside implicit Euler's matrix.
SpectralRadius amplification_spectral_radius(Integrator integrator,
                                             const SparseMatrix& K_weighted,
                                             const Eigen::VectorXd& rate, double h,
                                             const SparseMatrix* damping = nullptr);

/// The same operator as a dense matrix, for tests on small meshes only. Both act on
/// (y, h y'), which is similar to the step on (y, y') (same eigenvalues) and keeps every
/// block of the order of h^2 A and h C.
Eigen::MatrixXd amplification_matrix_dense(Integrator integrator, const SparseMatrix& K_weighted,
                                           const Eigen::VectorXd& rate, double h,
                                           const SparseMatrix* damping = nullptr);

/// c_i = gamma_i / m_i repeated for the 3 dofs of each free node.
Eigen::VectorXd damping_rates(const Model& model, const std::vector<double>& gamma);

}  // namespace dampbound
