#pragma once
// Exact linear stability of a step (SPEC 7): linearise the internal forces at a state
// (tangent stiffness K), take the largest eigenvalue lambda_max of M^-1 K with an iterative
// solver (never a dense decomposition of a large mesh), and from it the exact damping
// interval and the largest stable dt. Per-integrator mode analysis is in
// linear_stability_modes.hpp; docs/criteria.md has the derivations.
#include "dampbound/physics/export.hpp"
#include <Eigen/SparseCore>
#include <limits>
#include <optional>
#include <vector>

#include "dampbound/physics/closed_forms.hpp"
#include "dampbound/physics/model.hpp"
#include "dampbound/physics/stiffness.hpp"

namespace dampbound DAMPBOUND_API {

/// A proved lower bound on lambda_min of M^-1 K at x (1/s^2), from the splitting
/// K = diag(kappa_a,i I) + sum of the spring blocks B: B's eigenvalues are kappa (1 - l0/l)
/// (twice) and kappa, so with no spring compressed every B is positive semidefinite and
/// lambda_min >= min_i kappa_a,i / m_i over the free nodes. Springs shorter than their rest
/// length only by rounding (1 - l0/l >= -1e-12) are allowed, less a bound on their part;
/// with a compressed spring (and no `clamp_compression`), or no free node: nullopt.
std::optional<double> psd_floor(const Model& model, const std::vector<Vec3>& x,
                                bool clamp_compression = false);

/// Spring k's part of K at x (SPEC 7's block B on its two nodes: [B, -B; -B, B]) raised to
/// its positive part B+ >= B: B itself unless the spring is compressed, then kappa d d^T.
/// False (B untouched) for a spring of no direction (SPEC 1), which has no part in K.
bool positive_spring_block(const Model& model, const std::vector<Vec3>& x, size_t k,
                           Eigen::Matrix3d& B);

/// Proved upper bounds from the splitting that psd_floor bounds from below. A spring's part
/// of K, [B, -B; -B, B] on its two nodes, lies below [2B+, 0; 0, 2B+] (B+ the positive part
/// of B: [X, -X; -X, X] <= [X, X; X, X] + [X, -X; -X, X] = 2 diag(X, X) for X >= 0), and
/// below B+ on its free node alone when the other is fixed. So K <= blockdiag(D_i), D_i =
/// 2 sum_j B_ij+ + kappa_a,i I (B_ij+ undoubled towards a fixed node), and with M's blocks
/// m_i I every eigenvalue of M^-1 K, and of SPEC 7's index matrix dt^2 A + 2 dt C, is at
/// most max_i of lambda_max(D_i) / m_i and of dt^2 lambda_max(D_i) / m_i + 2 dt c_i.
/// `ceiling` receives per node lambda_max(D_i) / m_i (1/s^2; 0 for a fixed node), each raised
/// by 1e-12 of the largest trace(D_i) / m_i for the rounding of the sums, of the 3 x 3
/// eigenvalues and of A's own entries. Any state, compressed springs included. On 3-D meshes
/// it lies well below Gershgorin's bound (tissue block: 22 % above lambda_max against 42 %),
/// on a flat plane at rest level with it (docs/criteria.md, "Over the factorisation budget").
void splitting_ceilings(const Model& model, const std::vector<Vec3>& x,
                        std::vector<double>& ceiling);

/// Largest and smallest algebraic eigenvalue of a symmetric sparse matrix, each the safe end
/// of a certified interval (linear_stability_cholesky.hpp: shift-and-invert Lanczos from
/// Gershgorin's bound, a Cholesky certificate): largest_eigenvalue is never low and
/// smallest_eigenvalue never high, by at most ~1e-10 relative. Dense up to 400 rows.
double largest_eigenvalue(const SparseMatrix& A);
double smallest_eigenvalue(const SparseMatrix& A);
/// The smallest eigenvalue above `floor` (zero modes skipped: motions no spring resists).
/// Dense up to 300 rows, else the 12 smallest by Lanczos; NaN when none is found.
double smallest_eigenvalue_above(const SparseMatrix& A, double floor);
/// The largest eigenvalue (certified upper end) and its unit Ritz vector (for
/// Hellmann-Feynman slopes). `threads` and `max_factor_flops` (infinite: no limit) as in
/// certified_largest_eigenvalue.
double largest_eigenpair(const SparseMatrix& A, Eigen::VectorXd& vector, int threads = 1,
                         double max_factor_flops = std::numeric_limits<double>::infinity());

/// Largest eigenvalue of M^-1 K, K the tangent stiffness of springs and anchors at positions
/// x (at rest only spring directions and anchors contribute), over the free nodes.
/// Units 1/s^2. The upper end of a certified interval, ~1e-10 relative wide.
double max_stiffness_eigenvalue(const Model& model, const std::vector<Vec3>& x);

/// Both ends of the spectrum of M^-1 K at x (1/s^2): what the per-mode analysis of any
/// integrator needs when gamma/m is uniform.
struct StiffnessSpectrum {
  double lambda_min = 0;
  double lambda_max = 0;
};
StiffnessSpectrum stiffness_spectrum(const Model& model, const std::vector<Vec3>& x);

/// Non-uniform damping (gamma_i/m_i not all equal) for the semi-implicit step. With all
/// c_i = gamma_i/m_i > 0 and K positive definite, the step is stable iff
///   S = dt^2 M^-1/2 K M^-1/2 + 2 dt M^-1 Gamma  has every eigenvalue < 4
/// (an eigenvalue of the amplification matrix can leave the unit disc only through z = -1,
/// where det(4M - 2 dt Gamma - dt^2 K) = 0; docs/criteria.md). Returns lambda_max(S).
/// `gamma` holds gamma_i per node (fixed nodes ignored).
double semi_implicit_stability_index(const Model& model, const SparseMatrix& K_weighted,
                                     const std::vector<double>& gamma, double dt);

}  // namespace dampbound
