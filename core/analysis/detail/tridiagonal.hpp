#pragma once
// What the shift placement needs from Lanczos's symmetric tridiagonal T (diagonal
// alpha[0..m), off-diagonal beta[0..m-1)): its largest eigenvalue, by bisection on Sturm
// counts, and that eigenvalue's unit eigenvector, by inverse iteration (the Lanczos residual
// is |beta_m| times its last component; the bound without a factorisation forms its Ritz
// vector). Bisection cannot fail to converge; the QR iteration of a
// general tridiagonal eigensolver can, on the nearly repeated Ritz values that Lanczos without
// reorthogonalisation makes (it did, on tissue-cap's -A).
#include <vector>

namespace dampbound::detail {

/// How many eigenvalues of T lie below x (the negative pivots of T - x I = L D L^T).
int eigenvalues_below(const double* alpha, const double* beta, int m, double x);

/// The largest eigenvalue of T, to a few units in the last place of its size. m >= 1.
double largest_tridiagonal_eigenvalue(const double* alpha, const double* beta, int m);

/// |y_m| for the unit eigenvector y of T belonging to its eigenvalue theta: three steps of
/// inverse iteration with T - theta I (Gaussian elimination with row interchanges). m >= 1.
double last_eigenvector_component(const double* alpha, const double* beta, int m, double theta);

/// The unit eigenvector y of T belonging to its eigenvalue theta, by the same inverse
/// iteration (empty when it breaks down). m >= 1.
std::vector<double> tridiagonal_eigenvector(const double* alpha, const double* beta, int m,
                                            double theta);

}  // namespace dampbound::detail
