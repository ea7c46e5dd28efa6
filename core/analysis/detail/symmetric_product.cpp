#include "core/analysis/detail/symmetric_product.hpp"

#include <algorithm>

namespace dampbound::detail {
namespace {

size_t block_count(Eigen::Index rows, size_t block_rows) {
  return (static_cast<size_t>(rows) + block_rows - 1) / block_rows;
}

/// Calls row_term(r) for the rows of each block in order and stores the block's sum of the
/// returned terms in partial[block] (four accumulators, kSumBlockRows says how); returns the
/// sum of the partials in block order.
template <class RowTerm>
double blocked_sum(Eigen::Index rows, size_t block_rows, std::vector<double>& partial,
                   NodeThreads& threads, const RowTerm& row_term) {
  const size_t blocks = block_count(rows, block_rows);
  partial.assign(blocks, 0.0);
  const size_t n = static_cast<size_t>(rows);
  threads.run(blocks, [&](int, size_t first_block, size_t end_block) {
    for (size_t k = first_block; k < end_block; ++k) {
      double s[4] = {0, 0, 0, 0};
      const size_t end = std::min(n, (k + 1) * block_rows);
      for (size_t r = k * block_rows; r < end; ++r) s[r & 3] += row_term(r);
      partial[k] = (s[0] + s[1]) + (s[2] + s[3]);
    }
  });
  double sum = 0;
  for (double x : partial) sum += x;
  return sum;
}

}  // namespace

double product_and_dot(const SymmetricOperator& S, const Eigen::VectorXd& v, double b,
                       const Eigen::VectorXd& p, Eigen::VectorXd& w, std::vector<double>& partial,
                       NodeThreads& threads, size_t block_rows) {
  const SparseMatrix& A = S.A;
  w.resize(A.rows());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* value = A.valuePtr();
  const int* count = A.innerNonZeroPtr();  // null when compressed (assembled matrices are)
  const double* d = S.d ? S.d->data() : nullptr;
  const double scale = S.scale;
  return blocked_sum(A.rows(), block_rows, partial, threads, [&](size_t r) {
    const int first = outer[r];
    const int last = count ? first + count[r] : outer[r + 1];
    double sum = 0;
    for (int k = first; k < last; ++k) sum += value[k] * v[inner[k]];
    const Eigen::Index i = static_cast<Eigen::Index>(r);
    const double x = d ? (scale * sum + d[r] * v[i]) - b * p[i] : sum - b * p[i];
    w[i] = x;
    return x * v[i];
  });
}

double subtract_and_square(Eigen::VectorXd& w, double a, const Eigen::VectorXd& v,
                           std::vector<double>& partial, NodeThreads& threads, size_t block_rows) {
  return blocked_sum(w.size(), block_rows, partial, threads, [&](size_t r) {
    const Eigen::Index i = static_cast<Eigen::Index>(r);
    const double x = w[i] - a * v[i];
    w[i] = x;
    return x * x;
  });
}

void divide(const Eigen::VectorXd& w, double b, Eigen::VectorXd& out, NodeThreads& threads,
            size_t block_rows) {
  out.resize(w.size());
  const size_t n = static_cast<size_t>(w.size());
  threads.run(block_count(w.size(), block_rows), [&](int, size_t first_block, size_t end_block) {
    const size_t end = std::min(n, end_block * block_rows);
    for (size_t r = first_block * block_rows; r < end; ++r)
      out[static_cast<Eigen::Index>(r)] = w[static_cast<Eigen::Index>(r)] / b;
  });
}

}  // namespace dampbound::detail
