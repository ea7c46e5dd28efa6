#pragma once
// The top eigenvector of (shift I - A)^-1 from a factorisation of shift I - A: shift-and-
// invert, whose largest eigenvalue 1 / (shift - lambda) belongs to the eigenvalue lambda of A
// nearest below the shift. certified_largest_eigenvalue takes its Rayleigh quotient in A as
// the interval's lower end (linear_stability_cholesky.cpp).
#include <Eigen/Core>

#include "core/analysis/detail/shifted_cholesky.hpp"

namespace dampbound::detail {

/// Solves before the short Lanczos below hands over to Spectra's restarted one.
inline constexpr int kShortSteps = 8;
/// The short Lanczos stops when the top Ritz pair (theta, u) of (shift I - A)^-1 has a
/// residual below kShortTolerance theta. By Davis and Kahan, u then lies within an angle
/// of sine kShortTolerance mu_1 / (mu_1 - mu_2) of the top eigenvector (mu the eigenvalues of
/// the inverse, mu_1 = 1 / (shift - lambda_max)), so its Rayleigh quotient in A falls short of
/// lambda_max by at most that sine squared times A's spread: below the certificate's width
/// (1e-10 relative) while the shift lies within 100 times the distance from lambda_max to the
/// next eigenvalue below it.
inline constexpr double kShortTolerance = 1e-7;

/// Lanczos on (shift I - A)^-1 with full reorthogonalisation (twice), from `start`, testing the
/// top Ritz pair after every solve: the fewest solves that reach `tol`, where Spectra's
/// restarted Lanczos builds its whole Krylov space of 8 first. False (u untouched) when
/// kShortSteps solves do not reach it.
bool short_inverse_lanczos(ShiftedCholesky& f, const Eigen::VectorXd& start, Eigen::VectorXd& u,
                           double tol);

/// The top Ritz vector of (shift I - A)^-1 from `u` (empty: Spectra's start), to relative
/// tolerance `tol`; inverse iteration when Lanczos does not converge in its budget.
void inverse_lanczos(ShiftedCholesky& f, Eigen::VectorXd& u, double tol);

}  // namespace dampbound::detail
