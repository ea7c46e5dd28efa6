#pragma once
// The passes of one Lanczos step on node threads, for a symmetric sparse A: the product
// w = A v - b p with the bits of Eigen's serial `w = A * v; w -= b * p`, then w -= a v and
// v' = w / beta, with the step's two sums (alpha = w . v, beta^2 = w . w) formed alongside.
// Every sum is split into blocks of rows fixed by the matrix alone, so it has the same bits on
// any thread count. The same passes in single precision (A's values rounded to float, float
// vectors, the sums in double) serve the estimate that only places a shift: a Lanczos step
// there is memory-bound, and moves about half the bytes.
#include <cstddef>
#include <vector>

#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/node_threads.hpp"

namespace dampbound::detail {

/// Rows per block of the step's sums: within a block the products are added in row order into
/// four accumulators (row index mod 4), combined as (s0 + s1) + (s2 + s3); the blocks' partial
/// sums are then added in block order. The passes run the blocks in `threads`' chunks, so its
/// grain counts blocks.
inline constexpr std::size_t kSumBlockRows = 4096;

/// The operator of a Lanczos step: S = scale A + diag(d), or A itself when d is null (and
/// scale is 1). A must be exactly symmetric (A_rs and A_sr the same bits, as every assembled
/// stiffness and its shifts are): row r of A v is summed over column r's entries in index
/// order, from 0, which is the order in which Eigen's column-major product adds A_rs v_s
/// into w_r.
struct SymmetricOperator {
  const SparseMatrix& A;
  double scale = 1;
  const Eigen::VectorXd* d = nullptr;
};

/// w = S v - b p, row by row (with d: (scale (A v)_r + d_r v_r) - b p_r); returns w . v.
/// `partial` holds the blocks' sums (resized here); w is resized to A's rows.
double product_and_dot(const SymmetricOperator& S, const Eigen::VectorXd& v, double b,
                       const Eigen::VectorXd& p, Eigen::VectorXd& w, std::vector<double>& partial,
                       NodeThreads& threads, std::size_t block_rows = kSumBlockRows);

/// A vector of either precision (Scalar: double or float, instantiated in the .cpp).
template <typename Scalar>
using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

/// w -= a v; returns w . w (after the subtraction), each square and the sum in double.
template <typename Scalar>
double subtract_and_square(Vector<Scalar>& w, Scalar a, const Vector<Scalar>& v,
                           std::vector<double>& partial, NodeThreads& threads,
                           std::size_t block_rows = kSumBlockRows);

/// out = w / b, element by element (out resized to w's size).
template <typename Scalar>
void divide(const Vector<Scalar>& w, Scalar b, Vector<Scalar>& out, NodeThreads& threads,
            std::size_t block_rows = kSumBlockRows);

/// A in single precision: A's pattern (not copied) and `values`, A's values rounded to float in
/// A's order. Row r of A v is summed in float over column r's entries in index order.
struct SingleOperator {
  const SparseMatrix& A;
  const float* values;
};

/// The product above in single precision: each row's value is rounded to float, and the sum
/// is of the rows' float values multiplied in double, in the blocked order above
/// (subtract_and_square and divide take float vectors as they are).
double product_and_dot(const SingleOperator& S, const Eigen::VectorXf& v, float b,
                       const Eigen::VectorXf& p, Eigen::VectorXf& w, std::vector<double>& partial,
                       NodeThreads& threads, std::size_t block_rows = kSumBlockRows);

}  // namespace dampbound::detail
