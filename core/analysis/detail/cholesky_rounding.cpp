#include "core/analysis/detail/cholesky_rounding.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace dampbound::detail {
namespace {

/// add_block: one dense block of L's columns (a supernode, or one simplicial column), stored
/// by columns with leading dimension `height`; rows[t] is the row of entry t in every column,
/// and the first `columns` rows are the block's own columns (entries above the diagonal
/// unused). Adds each row's stored entries and |L| (|L|^T 1) over these columns: a column's
/// sum of |L| needs only its own block.
struct Sums {
  std::vector<double> row_sum;
  std::vector<long long> row_entries;
  std::vector<double> column_sum;  // scratch: the block's column sums of |L|
  void add_block(const int* rows, int height, int columns, const double* x) {
    column_sum.assign(static_cast<size_t>(columns), 0.0);
    for (int c = 0; c < columns; ++c) {
      const double* col = x + static_cast<size_t>(c) * static_cast<size_t>(height);
      for (int t = c; t < height; ++t) column_sum[static_cast<size_t>(c)] += std::abs(col[t]);
    }
    for (int c = 0; c < columns; ++c) {
      const double* col = x + static_cast<size_t>(c) * static_cast<size_t>(height);
      for (int t = c; t < height; ++t)
        row_sum[static_cast<size_t>(rows[t])] += std::abs(col[t]) * column_sum[static_cast<size_t>(c)];
    }
    for (int t = 0; t < height; ++t)
      row_entries[static_cast<size_t>(rows[t])] += t < columns ? t + 1 : columns;
  }
};

}  // namespace

double cholesky_rounding_bound(const cholmod_factor_struct& L, double max_abs_diagonal) {
  if (!L.is_ll || L.itype != CHOLMOD_INT || L.xtype != CHOLMOD_REAL || L.dtype != CHOLMOD_DOUBLE)
    throw std::invalid_argument("cholesky_rounding_bound: not a real double LL' factor of int indices");
  const size_t n = L.n;
  Sums sums;
  sums.row_sum.assign(n, 0.0);
  sums.row_entries.assign(n, 0);
  const double* x = static_cast<const double*>(L.x);
  if (L.is_super) {  // supernode s: columns super[s].., rows s[pi[s]..], values x[px[s]..]
    const int* super = static_cast<const int*>(L.super);
    const int* pi = static_cast<const int*>(L.pi);
    const int* px = static_cast<const int*>(L.px);
    const int* rows = static_cast<const int*>(L.s);
    for (size_t s = 0; s < L.nsuper; ++s)
      sums.add_block(rows + pi[s], pi[s + 1] - pi[s], super[s + 1] - super[s], x + px[s]);
  } else {  // column j: rows i[p[j]..], its diagonal first, nz[j] entries
    const int* p = static_cast<const int*>(L.p);
    const int* i = static_cast<const int*>(L.i);
    const int* nz = static_cast<const int*>(L.nz);
    for (size_t j = 0; j < n; ++j) sums.add_block(i + p[j], nz[j], 1, x + p[j]);
  }
  const double largest = n ? *std::max_element(sums.row_sum.begin(), sums.row_sum.end()) : 0.0;
  const long long longest =
      n ? *std::max_element(sums.row_entries.begin(), sums.row_entries.end()) : 0;
  return rounding_bound(largest, longest, max_abs_diagonal);
}

double rounding_bound(double largest_row_sum, long long longest_row, double max_abs_diagonal) {
  const double u = std::numeric_limits<double>::epsilon() / 2;
  const double m = 2.0 * static_cast<double>(longest_row) + 4.0;
  if (!(m * u < 0.5)) return std::numeric_limits<double>::infinity();
  const double gamma = m * u / (1 - m * u);
  return (gamma * largest_row_sum + u * max_abs_diagonal) * (1 + 1e-6);
}

}  // namespace dampbound::detail
