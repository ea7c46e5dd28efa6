#include "core/analysis/detail/supernodal_solve.hpp"

#include <cholmod.h>

#include <stdexcept>

extern "C" {  // the BLAS CHOLMOD itself calls (Fortran interface)
void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a,
            const int* lda, double* x, const int* incx);
void dgemv_(const char* trans, const int* m, const int* n, const double* alpha, const double* a,
            const int* lda, const double* x, const int* incx, const double* beta, double* y,
            const int* incy);
}

namespace dampbound::detail {
namespace {

/// Supernodes of at least this many columns go to BLAS (dtrsv, dgemv), whose blocked kernels
/// win there; below it the loops here win. Alternating thresholds of 8 to 64 on a 200 x 200
/// and a 400 x 400 plane and 20^3 and 30^3 blocks: 32 was the best or within noise on all four.
constexpr int kBlasColumns = 32;

/// The sum of a[i] * b[i] over i < n in four interleaved partial sums.
inline double dot(const double* a, const double* b, int n) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += a[i] * b[i];
    s1 += a[i + 1] * b[i + 1];
    s2 += a[i + 2] * b[i + 2];
    s3 += a[i + 3] * b[i + 3];
  }
  for (; i < n; ++i) s0 += a[i] * b[i];
  return (s0 + s1) + (s2 + s3);
}

/// Supernode s of L: its first column, columns, stored rows (its columns', then `below` rows
/// below them) and values (column-major, leading dimension `height`).
struct Supernode {
  int k1, columns, height, below;
  const int* below_rows;
  const double* values;
  Supernode(const cholmod_factor_struct& L, size_t s) {
    const int* super = static_cast<const int*>(L.super);
    const int* pi = static_cast<const int*>(L.pi);
    k1 = super[s];
    columns = super[s + 1] - k1;
    height = pi[s + 1] - pi[s];
    below = height - columns;
    below_rows = static_cast<const int*>(L.s) + pi[s] + columns;
    values = static_cast<const double*>(L.x) + static_cast<const int*>(L.px)[s];
  }
};

}  // namespace

void supernodal_solve(const cholmod_factor_struct& L, const double* b, double* x,
                      std::vector<double>& work) {
  if (!L.is_super || !L.is_ll || L.itype != CHOLMOD_INT || L.xtype != CHOLMOD_REAL ||
      L.dtype != CHOLMOD_DOUBLE || L.minor < L.n)
    throw std::invalid_argument("supernodal_solve: not a successful real supernodal LL' factor");
  const size_t n = L.n;
  const int* perm = static_cast<const int*>(L.Perm);
  work.resize(n + L.maxesize);
  double* y = work.data();  // the permuted right-hand side, then the solution
  double* e = y + n;        // one supernode's rows below its columns
  for (size_t i = 0; i < n; ++i) y[i] = b[perm[i]];
  // L y' = y: supernode by supernode, its columns (a dense lower triangle), then what they
  // take from the rows below, gathered in e and subtracted once per row.
  for (size_t s = 0; s < L.nsuper; ++s) {
    const Supernode sn(L, s);
    const int columns = sn.columns, height = sn.height, below = sn.below;
    const int* r = sn.below_rows;
    const double* Ls = sn.values;
    double* ys = y + sn.k1;
    if (columns >= kBlasColumns) {
      const int one = 1;
      const double plus = 1, zero = 0;
      dtrsv_("L", "N", "N", &columns, Ls, &height, ys, &one);
      if (below > 0) {
        dgemv_("N", &below, &columns, &plus, Ls + columns, &height, ys, &one, &zero, e, &one);
        for (int t = 0; t < below; ++t) y[r[t]] -= e[t];
      }
      continue;
    }
    for (int t = 0; t < below; ++t) e[t] = 0;
    for (int j = 0; j < columns; ++j) {
      const double* col = Ls + static_cast<size_t>(j) * static_cast<size_t>(height);
      const double yj = ys[j] / col[j];
      ys[j] = yj;
      for (int i = j + 1; i < columns; ++i) ys[i] -= col[i] * yj;
      for (int t = 0; t < below; ++t) e[t] += col[columns + t] * yj;
    }
    for (int t = 0; t < below; ++t) y[r[t]] -= e[t];
  }
  // L^T x = y': backwards, each supernode's columns first take the rows below (gathered in
  // e), then its triangle from its last column to its first.
  for (size_t s = L.nsuper; s-- > 0;) {
    const Supernode sn(L, s);
    const int columns = sn.columns, height = sn.height, below = sn.below;
    const int* r = sn.below_rows;
    const double* Ls = sn.values;
    double* ys = y + sn.k1;
    for (int t = 0; t < below; ++t) e[t] = y[r[t]];
    if (columns >= kBlasColumns) {
      const int one = 1;
      const double minus = -1, plus = 1;
      if (below > 0)
        dgemv_("T", &below, &columns, &minus, Ls + columns, &height, e, &one, &plus, ys, &one);
      dtrsv_("L", "T", "N", &columns, Ls, &height, ys, &one);
      continue;
    }
    for (int j = columns - 1; j >= 0; --j) {
      const double* col = Ls + static_cast<size_t>(j) * static_cast<size_t>(height);
      const double sum =
          dot(col + columns, e, below) + dot(col + j + 1, ys + j + 1, columns - j - 1);
      ys[j] = (ys[j] - sum) / col[j];
    }
  }
  for (size_t i = 0; i < n; ++i) x[perm[i]] = y[i];
}

}  // namespace dampbound::detail
