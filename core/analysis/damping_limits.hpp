#pragma once
// SPEC 10's damping ratios and the exact limits of the paper's step with a general damping
// matrix C = Gamma + C' (dashpots, Rayleigh): stable iff lambda_max(dt^2 A + 2 dt C^) < 4 when
// K is positive semi-definite and C^ positive definite; the Rayleigh closed forms where C^
// commutes with A (no dashpot, uniform gamma_i / m_i).
#include <limits>
#include <memory>
#include <vector>

#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/model.hpp"

namespace dampbound {

/// No limit on one factorisation's cost (linear_stability_cholesky.hpp's kNoFactorBudget).
inline constexpr double kUnboundedFactor = std::numeric_limits<double>::infinity();

/// Damping ratios (SPEC 10) at positions x.
struct DampingRatios {
  double nodal_min = 0, nodal_max = 0;      ///< gamma_i / (2 sqrt(m_i kappa_i)), free nodes
  int dashpots = 0;                         ///< springs and anchors with kd > 0
  double dashpot_min = 0, dashpot_max = 0;  ///< kd_ij / (2 sqrt(mu_ij kappa_ij))
  double lambda_min = 0, lambda_max = 0;    ///< ends of the spectrum of M^-1 K (1/s^2)
  double rayleigh_low = 0, rayleigh_high = 0;  ///< (alpha + beta lambda) / (2 sqrt(lambda)) there
};
DampingRatios damping_ratios(const Model& model, const std::vector<Vec3>& x);
/// The same with the certified spectrum of M^-1 K at x already known (exact_stability's).
DampingRatios damping_ratios(const Model& model, const std::vector<Vec3>& x,
                             const StiffnessSpectrum& spectrum);

/// The exact limits of the paper's step with the model's damping (SPEC 10).
struct GeneralLimits {
  double index = 0;       ///< lambda_max(dt^2 A + 2 dt C^) at the model's gamma_i; stable below 4
  bool commuting = false; ///< C^ commutes with A: the Rayleigh closed forms were used
  double gamma_max = 0;   ///< the user's gamma below which the step is stable (may be <= 0)
  double dt_max = 0;      ///< the largest stable dt at the model's damping (s)
  /// A certified lower end of lambda_min(C^) (1/s): <= 0 leaves modes undamped (marginal).
  /// The eigenvalue's own lower end, or where the model's parts prove it positive (Weyl's
  /// floor, damping_floor below) that floor, and nothing factorised for it.
  double damping_min = 0;
};

namespace detail {
class ShiftedCholesky;
}

/// Factorisations kept between limit searches on one model (its damping kinds, the
/// ceilings): each search on the pattern analysed before goes on with that analysis and the
/// factor's memory instead of analysing anew; another pattern is analysed then.
class SharedFactors {
 public:
  SharedFactors();
  ~SharedFactors();
  SharedFactors(const SharedFactors&) = delete;
  SharedFactors& operator=(const SharedFactors&) = delete;
  std::unique_ptr<detail::ShiftedCholesky> factors;
};

/// Limits at positions x for step params.dt; gamma_i = gamma * gamma_scale_i. The index and
/// lambda_min(C^) are certified eigenvalues (linear_stability.hpp); the general case finds the
/// gamma and dt limits as the largest values at which 4 I - (dt^2 A + 2 dt C^) is proved
/// positive definite (detail/definite_root.hpp: a few factorisations on one pattern analysis),
/// each within 1e-10 relative of a value not proved so. `max_factor_flops` bounds every
/// factorisation of this function and of those below: FactorisationOverBudget is thrown when
/// CHOLMOD's pattern analysis predicts one over it, before that one is done.
GeneralLimits general_limits(const Model& model, const std::vector<Vec3>& x, const Params& params,
                             double max_factor_flops = kUnboundedFactor);
/// The same with the certified spectrum of A at x already known (exact_stability's), and
/// optionally the factors of its computation (`factors`): where the index matrix has A's
/// pattern (dashpots and Rayleigh damping on every spring), the index and the searches go on
/// with their pattern analysis instead of one of their own. Where C^
/// commutes with A (no dashpot, and gamma = 0 or gamma_i / m_i uniform) the index, dt_max and
/// lambda_min(C^) are SPEC 10's closed forms in its ends (no eigenvalue computed): the index
/// f(lambda_max), f(lambda) = dt^2 lambda + 2 dt (c0 + beta lambda) increasing in lambda, and
/// lambda_min(C^) = c0 + beta lambda_min, c0 = gamma_i / m_i + alpha. At gamma = 0 with
/// non-uniform gamma_scale_i / m_i, gamma_max still needs the search (`commuting` false).
GeneralLimits general_limits(const Model& model, const std::vector<Vec3>& x, const Params& params,
                             const StiffnessSpectrum& spectrum,
                             double max_factor_flops = kUnboundedFactor,
                             std::unique_ptr<detail::ShiftedCholesky>* factors = nullptr);

/// The general case on matrices (what the model's overload runs when C^ does not commute with
/// A, and linear_limits on a user's C): A = M^-1/2 K M^-1/2, Cp = M^-1/2 C' M^-1/2 (the damping
/// besides the nodal one), G the nodal damping per unit gamma (M^-1/2 diag(scale_i) M^-1/2),
/// for nodal damping gamma * G at step dt. `commuting` is false. `factors`: as above (the
/// pattern analysis of a matrix of the index's pattern, kept for the caller); `damping_floor`:
/// a proved lower bound of lambda_min(Cp + gamma G), which stands for it where positive
/// (NaN: none; the eigenvalue is certified).
GeneralLimits general_limits(const SparseMatrix& A, const SparseMatrix& Cp, const SparseMatrix& G,
                             double gamma, double dt, double max_factor_flops = kUnboundedFactor,
                             std::unique_ptr<detail::ShiftedCholesky>* factors = nullptr,
                             double damping_floor = std::numeric_limits<double>::quiet_NaN());

/// Weyl's floor of lambda_min(C^) for the model's damping at x with user gamma `gamma`:
/// C^ = alpha I + beta A + D + P with D diagonal ((gamma_i + kd_a,i) / m_i on node i's rows)
/// and P the spring dashpots' part (positive semi-definite: kd d d^T on each spring's
/// difference), so lambda_min(C^) >= alpha + beta lambda_min(A) + min_i D_ii, less a margin
/// of 1e-10 of C^'s and beta A's Gershgorin bounds for the rounding of the assembled entries.
/// `a_floor`: a proved lower bound of lambda_min(A). NaN where a part's sign is not known
/// (beta, alpha or a kd negative).
double damping_floor(const Model& model, double gamma, double a_floor, const SparseMatrix& A,
                     const SparseMatrix& C);

/// The largest coefficient x with lambda_max(dt^2 A + 2 dt (C + x U)) < 4 proved (A, C, U
/// positive semi-definite, so the index grows with x), within 1e-10 relative of one not
/// proved so (detail/definite_root.hpp): 0 when x = 0 is not proved stable, +inf when U has no
/// direction that raises the index.
double largest_stable_coefficient(const SparseMatrix& A, const SparseMatrix& C,
                                  const SparseMatrix& U, double dt,
                                  double max_factor_flops = kUnboundedFactor,
                                  SharedFactors* shared = nullptr);

/// SPEC 10's damping kinds, each with the others held: the exact stable range [0, max) of
/// the kind's coefficient at params.dt, linearised at x (suggest prints them).
enum class DampingKind { nodal, dashpot, rayleigh_mass, rayleigh_stiffness };
const char* to_string(DampingKind kind);       ///< "gamma", "kd", "rayleigh_mass", ...
double& coefficient(Params& params, DampingKind kind);  ///< gamma, kd, alpha or beta
/// `shared`: the factorisations of the kinds before (SharedFactors).
double damping_kind_max(const ModelSpec& spec, const std::vector<Vec3>& x, const Params& params,
                        DampingKind kind, double max_factor_flops = kUnboundedFactor,
                        SharedFactors* shared = nullptr);

}  // namespace dampbound
