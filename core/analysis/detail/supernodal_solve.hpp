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
#include <cstddef>
#include <utility>
#include <vector>

#include "dampbound/physics/node_threads.hpp"

struct cholmod_factor_struct;

namespace dampbound::detail {

/// x = (P^T L L^T P)^-1 b for a numerically successful supernodal LL' factor of int indices
/// and real double values (P = L.Perm; b and x of L.n entries; they may be the same array).
/// `work` is scratch, resized here.
void supernodal_solve(const cholmod_factor_struct& L, const double* b, double* x,
                      std::vector<double>& work);

/// The supernodes of a factor split for solves on two threads: two bins of whole subtrees of
/// the supernodal elimination tree (each subtree a run of consecutive supernodes: CHOLMOD
/// numbers them in postorder) and the top, every supernode above them. A bin's supernodes
/// write only their own subtrees' rows and the top's, so a forward solve runs the two bins at
/// once, each gathering its terms for the top's rows, then the top; a backward solve the top,
/// then the bins at once. Made from the factor's pattern alone: the bits of a solve do not
/// depend on the thread count.
struct SolveSplit {
  std::vector<std::pair<int, int>> bins[2];  ///< [first, last] supernode runs, ascending
  std::vector<int> top;                      ///< the top's supernodes, ascending
  std::vector<int> top_index;                ///< per row: its place among the top's rows, or -1
  std::vector<int> top_rows;                 ///< the top's rows (its supernodes' columns)
  bool empty() const { return bins[0].empty() && bins[1].empty(); }
};

/// Factors of fewer entries are solved serially: below a million entries a solve is too
/// short for a second thread to pay for itself.
inline constexpr std::size_t kSplitEntries = std::size_t{1} << 20;
/// Subtrees taken apart from the root down at most this many times.
inline constexpr int kSplitRounds = 64;
/// A split is kept when the top plus the heavier bin is under this share of the work, and
/// the bins' supernodes of 32 columns or more (BLAS in a serial solve, the loops in bin 1)
/// hold at most kSplitWideShare of it. Planes (about 40 % wide) gain from the second thread;
/// tetrahedral blocks (62 to 70 % wide) gain little and lose when the second core is busy,
/// so they stay serial (the measurements: docs/performance.md).
inline constexpr double kSplitWorthIt = 0.8;
inline constexpr double kSplitWideShare = 0.55;

/// The split whose top plus heavier bin is the least work (entries of L read), or an empty
/// one (serial solves): a small factor, supernodes not in postorder, no split worth a thread.
/// `min_entries`: the factor size from which to split (tests split small factors).
SolveSplit split_supernodes(const cholmod_factor_struct& L,
                            std::size_t min_entries = kSplitEntries);

/// As supernodal_solve, the two bins on `threads` (the same bits on one thread or two). BLAS
/// may be entered from one thread only (shifted_cholesky.cpp): bin 0, which runs on the
/// calling thread, and the top take it for their wide supernodes as supernodal_solve does;
/// bin 1, on the other thread, runs the plain loops whatever their width. `split` non-empty.
void supernodal_solve_split(const cholmod_factor_struct& L, const SolveSplit& split,
                            const double* b, double* x, std::vector<double>& work,
                            NodeThreads& threads);

}  // namespace dampbound::detail
