#pragma once
// The Lanczos step's matrix-vector product on node threads: w = A v - b p for a symmetric
// sparse A, with the bits of Eigen's serial `w = A * v; w -= b * p` on any thread count.
#include "core/analysis/linear_stability.hpp"
#include "core/node_threads.hpp"

namespace dampbound::detail {

/// w = A v - b p. A must be exactly symmetric (A_rs and A_sr the same bits, as every
/// assembled stiffness and its shifts are): row r is summed over column r's entries in index
/// order, from 0, which is the order in which Eigen's column-major product adds A_rs v_s into
/// w_r. Rows are split into `threads`' contiguous chunks (its grain decides how many); w is
/// resized to A's rows.
void symmetric_product(const SparseMatrix& A, const Eigen::VectorXd& v, double b,
                       const Eigen::VectorXd& p, Eigen::VectorXd& w, NodeThreads& threads);

}  // namespace dampbound::detail
