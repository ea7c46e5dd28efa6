#pragma once
// Solves with CHOLMOD's supernodal LL' factor, for the shift-and-invert steps of
// certified_largest_eigenvalue. CHOLMOD's own solve calls BLAS (a triangular solve and a
// matrix-vector product) once per supernode each way; the factor of a 200 x 200 plane has
// 47 496 supernodes, 40 403 of one column, so those calls, not the 63 MB of the factor, set
// the time (docs/performance.md, "Solves"). Here a supernode of fewer than 32 columns is a
// few plain loops over its columns, a bigger one the same BLAS calls as CHOLMOD's. Nothing
// certified rests on a solve: it only steers the vector whose Rayleigh quotient and
// factorisation prove the interval (linear_stability_cholesky.cpp). It calls BLAS, so it runs
// in CHOLMOD's turn (shifted_cholesky.cpp).
#include <vector>

struct cholmod_factor_struct;

namespace dampbound::detail {

/// x = (P^T L L^T P)^-1 b for a numerically successful supernodal LL' factor of int indices
/// and real double values (P = L.Perm; b and x of L.n entries; they may be the same array).
/// `work` is scratch, resized here.
void supernodal_solve(const cholmod_factor_struct& L, const double* b, double* x,
                      std::vector<double>& work);

}  // namespace dampbound::detail
