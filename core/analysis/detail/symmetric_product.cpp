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

namespace {

/// w_r = row_value(r, sum over column r of A of value[k] v[inner[k]], summed in Value in
/// index order); returns the blocked sum of w_r v_r in double.
template <class Value, class Vector, class RowValue>
double product_pass(const SparseMatrix& A, const Value* value, const Vector& v, Vector& w,
                    std::vector<double>& partial, NodeThreads& threads, size_t block_rows,
                    const RowValue& row_value) {
  w.resize(A.rows());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const int* count = A.innerNonZeroPtr();  // null when compressed (assembled matrices are)
  return blocked_sum(A.rows(), block_rows, partial, threads, [&](size_t r) {
    const int first = outer[r];
    const int last = count ? first + count[r] : outer[r + 1];
    Value sum = 0;
    for (int k = first; k < last; ++k) sum += value[k] * v[inner[k]];
    const Eigen::Index i = static_cast<Eigen::Index>(r);
    const Value x = row_value(i, sum);
    w[i] = x;
    return static_cast<double>(x) * v[i];
  });
}

}  // namespace

double product_and_dot(const SymmetricOperator& S, const Eigen::VectorXd& v, double b,
                       const Eigen::VectorXd& p, Eigen::VectorXd& w, std::vector<double>& partial,
                       NodeThreads& threads, size_t block_rows) {
  const double* d = S.d ? S.d->data() : nullptr;
  const double scale = S.scale;
  return product_pass(S.A, S.A.valuePtr(), v, w, partial, threads, block_rows,
                      [&](Eigen::Index i, double sum) {
                        return d ? (scale * sum + d[i] * v[i]) - b * p[i] : sum - b * p[i];
                      });
}

double product_and_dot(const SingleOperator& S, const Eigen::VectorXf& v, float b,
                       const Eigen::VectorXf& p, Eigen::VectorXf& w, std::vector<double>& partial,
                       NodeThreads& threads, size_t block_rows) {
  return product_pass(S.A, S.values, v, w, partial, threads, block_rows,
                      [&](Eigen::Index i, float sum) { return sum - b * p[i]; });
}

template <typename Scalar>
double subtract_and_square(Vector<Scalar>& w, Scalar a, const Vector<Scalar>& v,
                           std::vector<double>& partial, NodeThreads& threads, size_t block_rows) {
  return blocked_sum(w.size(), block_rows, partial, threads, [&](size_t r) {
    const Eigen::Index i = static_cast<Eigen::Index>(r);
    const Scalar x = w[i] - a * v[i];
    w[i] = x;
    return static_cast<double>(x) * x;
  });
}

template <typename Scalar>
void divide(const Vector<Scalar>& w, Scalar b, Vector<Scalar>& out, NodeThreads& threads,
            size_t block_rows) {
  out.resize(w.size());
  const size_t n = static_cast<size_t>(w.size());
  threads.run(block_count(w.size(), block_rows), [&](int, size_t first_block, size_t end_block) {
    const size_t end = std::min(n, end_block * block_rows);
    for (size_t r = first_block * block_rows; r < end; ++r)
      out[static_cast<Eigen::Index>(r)] = w[static_cast<Eigen::Index>(r)] / b;
  });
}

template double subtract_and_square<double>(Vector<double>&, double, const Vector<double>&,
                                            std::vector<double>&, NodeThreads&, size_t);
template double subtract_and_square<float>(Vector<float>&, float, const Vector<float>&,
                                           std::vector<double>&, NodeThreads&, size_t);
template void divide<double>(const Vector<double>&, double, Vector<double>&, NodeThreads&, size_t);
template void divide<float>(const Vector<float>&, float, Vector<float>&, NodeThreads&, size_t);

}  // namespace dampbound::detail
