#pragma once
// What the shift placement needs from Lanczos's symmetric tridiagonal T (diagonal
// alpha[0..m), off-diagonal beta[0..m-1)): its largest eigenvalue and that eigenvalue's unit
// eigenvector (the Lanczos residual is |beta_m| times its last component; the bound without a
// factorisation forms its Ritz vector). LAPACK computes both: dstebz by bisection on Sturm
// counts, dstein by inverse iteration. Bisection cannot fail to converge; the QR iteration of
// a general tridiagonal eigensolver can, on the nearly repeated Ritz values that Lanczos
// without reorthogonalisation makes (it did, on tissue-cap's -A).
#include <vector>

namespace dampbound::detail {

/// T's largest eigenvalue, to a few units in the last place of T's norm (dstebz with the
/// tightest tolerance). NaN when T has an entry that is not finite. m >= 1.
double largest_tridiagonal_eigenvalue(const double* alpha, const double* beta, int m);

/// T's largest eigenvalue and its unit eigenvector (dstein; its largest entry positive).
struct TridiagonalTop {
  double value = 0;
  std::vector<double> vector;  ///< empty when inverse iteration failed or T is not finite
};
TridiagonalTop tridiagonal_top(const double* alpha, const double* beta, int m);

}  // namespace dampbound::detail
