#include "core/analysis/detail/tridiagonal.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

// LAPACK's Fortran entry points (Debian's liblapack.so.3: OpenBLAS's, or the reference one),
// with gfortran's hidden length of each character argument. They run outside CHOLMOD's turn
// (shifted_cholesky.cpp), beside a factorisation: dstebz calls no BLAS, dstein only level-1
// BLAS, which takes none of the work buffers that OpenBLAS shares between threads.
extern "C" {
double dlamch_(const char* cmach, std::size_t cmach_len);
void dstebz_(const char* range, const char* order, const int* n, const double* vl, const double* vu,
             const int* il, const int* iu, const double* abstol, const double* d, const double* e,
             int* m, int* nsplit, double* w, int* iblock, int* isplit, double* work, int* iwork,
             int* info, std::size_t range_len, std::size_t order_len);
void dstein_(const int* n, const double* d, const double* e, const int* m, const double* w,
             const int* iblock, const int* isplit, double* z, const int* ldz, double* work,
             int* iwork, int* ifail, int* info);
}

namespace dampbound::detail {
namespace {

/// dstebz's answer for the top eigenvalue: the value, its block and T's split points, which
/// dstein takes as they are.
struct Top {
  double value = std::numeric_limits<double>::quiet_NaN();
  int block = 0;
  std::vector<int> split;
};

Top top_by_bisection(const double* alpha, const double* beta, int m) {
  Top top;
  for (int i = 0; i < m; ++i)
    if (!std::isfinite(alpha[i]) || (i + 1 < m && !std::isfinite(beta[i]))) return top;
  // Only the m-th of m eigenvalues ("I", il = iu = m), ordered by block ("B", what dstein
  // takes), to twice the underflow threshold: as accurately as bisection can.
  const double abstol = 2 * dlamch_("S", 1);
  const double unused = 0;
  int found = 0, nsplit = 0, info = 0;
  top.split.resize(static_cast<size_t>(m));
  std::vector<int> blocks(static_cast<size_t>(m)), iwork(3 * static_cast<size_t>(m));
  std::vector<double> w(static_cast<size_t>(m)), work(4 * static_cast<size_t>(m));
  dstebz_("I", "B", &m, &unused, &unused, &m, &m, &abstol, alpha, beta, &found, &nsplit, w.data(),
          blocks.data(), top.split.data(), work.data(), iwork.data(), &info, 1, 1);
  if (info != 0 || found != 1) return top;
  top.value = w[0];
  top.block = blocks[0];
  return top;
}

}  // namespace

double largest_tridiagonal_eigenvalue(const double* alpha, const double* beta, int m) {
  return top_by_bisection(alpha, beta, m).value;
}

TridiagonalTop tridiagonal_top(const double* alpha, const double* beta, int m) {
  const Top top = top_by_bisection(alpha, beta, m);
  TridiagonalTop out;
  out.value = top.value;
  if (!std::isfinite(top.value)) return out;
  const int one = 1;
  std::vector<double> z(static_cast<size_t>(m)), work(5 * static_cast<size_t>(m));
  std::vector<int> iwork(static_cast<size_t>(m));
  int fail = 0, info = 0;
  dstein_(&m, alpha, beta, &one, &top.value, &top.block, top.split.data(), z.data(), &m,
          work.data(), iwork.data(), &fail, &info);
  if (info == 0) out.vector = std::move(z);
  return out;
}

}  // namespace dampbound::detail
