#include "core/analysis/detail/cholesky_rounding.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace dampbound::detail {
namespace {

/// Calls f(row, column, value) for every stored entry of L's lower triangle, column by column.
template <typename F>
void for_each_entry(const cholmod_factor& L, F&& f) {
  const double* x = static_cast<const double*>(L.x);
  if (L.is_super) {
    const int* super = static_cast<const int*>(L.super);
    const int* pi = static_cast<const int*>(L.pi);
    const int* px = static_cast<const int*>(L.px);
    const int* rows = static_cast<const int*>(L.s);
    for (size_t s = 0; s < L.nsuper; ++s) {
      const int first = super[s], columns = super[s + 1] - first;
      const int nsrow = pi[s + 1] - pi[s];
      const int* r = rows + pi[s];
      const double* block = x + px[s];  // nsrow x columns, by columns
      for (int c = 0; c < columns; ++c)
        for (int t = c; t < nsrow; ++t)  // above t = c: the diagonal block's unused half
          f(r[t], first + c, block[t + static_cast<size_t>(c) * static_cast<size_t>(nsrow)]);
    }
    return;
  }
  const int* p = static_cast<const int*>(L.p);
  const int* i = static_cast<const int*>(L.i);
  const int* nz = static_cast<const int*>(L.nz);
  for (size_t j = 0; j < L.n; ++j)
    for (int k = p[j]; k < p[j] + nz[j]; ++k) f(i[k], static_cast<int>(j), x[k]);
}

}  // namespace

double cholesky_rounding_bound(const cholmod_factor_struct& L, double max_abs_diagonal) {
  if (!L.is_ll || L.itype != CHOLMOD_INT || L.xtype != CHOLMOD_REAL || L.dtype != CHOLMOD_DOUBLE)
    throw std::invalid_argument("cholesky_rounding_bound: not a real double LL' factor of int indices");
  const size_t n = L.n;
  // |L|^T 1 (the column sums of |L|) and each row's stored entries.
  std::vector<double> column_sum(n, 0.0);
  std::vector<long long> row_entries(n, 0);
  for_each_entry(L, [&](int r, int c, double v) {
    column_sum[static_cast<size_t>(c)] += std::abs(v);
    ++row_entries[static_cast<size_t>(r)];
  });
  // |L| (|L|^T 1): row r's sum of |L_rc| times column c's sum.
  std::vector<double> row_sum(n, 0.0);
  for_each_entry(L, [&](int r, int c, double v) {
    row_sum[static_cast<size_t>(r)] += std::abs(v) * column_sum[static_cast<size_t>(c)];
  });
  const double largest = n ? *std::max_element(row_sum.begin(), row_sum.end()) : 0.0;
  const long long longest = n ? *std::max_element(row_entries.begin(), row_entries.end()) : 0;
  const double u = std::numeric_limits<double>::epsilon() / 2;
  const double m = 2.0 * static_cast<double>(longest) + 4.0;
  if (!(m * u < 0.5)) return std::numeric_limits<double>::infinity();
  const double gamma = m * u / (1 - m * u);
  return (gamma * largest + u * max_abs_diagonal) * (1 + 1e-6);
}

}  // namespace dampbound::detail
