#pragma once
// How far a successful sparse Cholesky factorisation can be from proving what it seems to
// prove (SPEC 7, 9): a factorisation of sigma I - A that succeeds says lambda_max(A) < sigma
// only in exact arithmetic. In floating point it proves lambda_max(A) < sigma + delta, with
// delta from the factor itself:
//
// CHOLMOD factors B~ = B + D (B = sigma I - A; its diagonal sigma - A_kk rounded once, so
// |D_kk| <= u |B~_kk|, u = eps / 2) into L L^T = P B~ P^T + E with |E| <= gamma_m |L| |L|^T
// entry by entry, gamma_m = m u / (1 - m u), m - 1 the longest inner product (Higham,
// "Accuracy and Stability of Numerical Algorithms", 2nd ed., Theorem 10.3; the order of the
// sums does not matter). Every pivot > 0 makes L L^T positive definite, so
//   lambda_min(B) > -(||E||_2 + ||D||_2) >= -(gamma_m max_i (|L| |L|^T 1)_i + u max_k |B~_kk|)
// (for a symmetric matrix ||.||_2 <= the largest row sum of |.|). m is taken as twice the
// longest row of L (its stored entries, explicit zeros included) plus 4: blocked kernels may
// round twice per term (OpenBLAS's triangular solves multiply by a reciprocal). The result is
// enlarged by 1e-6 relative for the rounding of its own sums.
struct cholmod_factor_struct;

namespace dampbound::detail {

/// delta for a numerically successful LL' factor (supernodal or simplicial) of a matrix whose
/// largest diagonal entry in magnitude, as factored, was `max_abs_diagonal`.
double cholesky_rounding_bound(const cholmod_factor_struct& L, double max_abs_diagonal);

/// The same delta from its parts, for any factor (ShiftedCholesky's, and the dense ones of
/// index_patch.cpp): `largest_row_sum` = max_i (|L| |L|^T 1)_i, `longest_row` the most entries
/// in a row of L, `max_abs_diagonal` as above.
double rounding_bound(double largest_row_sum, long long longest_row, double max_abs_diagonal);

}  // namespace dampbound::detail
