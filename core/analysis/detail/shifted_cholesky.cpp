#include "core/analysis/detail/shifted_cholesky.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

#include "core/analysis/detail/cholesky_rounding.hpp"
#include "core/analysis/detail/serial_openmp.hpp"
#include "core/analysis/detail/supernodal_solve.hpp"

namespace dampbound::detail {
namespace {

/// Below this many rows the fill-reducing ordering is AMD alone; from it on, CHOLMOD's default
/// (AMD, then METIS's nested dissection where AMD's fill is poor). A 3-D mesh pays from a few
/// thousand rows: tissue-block's 17010 rows factor in 1.81 GFlop with METIS against 6.75 with
/// AMD, and `bounds tissue-block` went from 3.46 to 2.84 s of CPU (tissue-block-rayleigh 2.42
/// to 1.57 s) when this was lowered from 20000; a plane's AMD fill is good, and CHOLMOD stops
/// at AMD there.
constexpr Eigen::Index kNestedDissectionRows = 2000;

/// The one turn in CHOLMOD, and in the libraries it calls, for the whole process: two analyses
/// may run at once (the tuner's analysis and Suggest workers, a user's own threads), and
/// - Debian's libopenblas0-serial (0.3.21, what scripts/install-deps.sh installs) shares its
///   work buffers between threads without a lock: two threads in it at once corrupt each
///   other's results, and a factorisation corrupted that way can succeed below lambda_max, a
///   false certificate;
/// - METIS, which CHOLMOD's analysis tries above 20 000 rows, draws from one random generator
///   for the process: two analyses at once order the matrix differently, so the results'
///   bits would depend on what else was running.
/// So every pattern analysis, numeric factorisation and solve takes this turn (measured:
/// docs/performance.md, "One thread in CHOLMOD at a time"); the Lanczos products, which call
/// none of these libraries, do not.
std::mutex& cholmod_turn() {
  static std::mutex turn;
  return turn;
}

/// CHOLMOD's prediction (flops, entries of L) for one factorisation of the lower triangle B in
/// AMD's ordering, the quick check of a big matrix's budget. When the rows come in threes (a
/// mesh's free nodes: x, y, z), AMD orders the graph of the nodes, node J joined to node K
/// when any of their rows couple, and the prediction is expanded to rows: a node column of c
/// nodes (its diagonal one included) stands for row columns of 3c, 3c - 1 and 3c - 2 entries,
/// and CHOLMOD counts a factorisation's flops as the sum of its columns' squares. The node
/// graph has about a ninth of the rows' entries, and AMD on it is several times faster than
/// on the rows (docs/performance.md). Otherwise AMD on the rows.
struct Prediction {
  double flops = 0, entries = 0;
};
Prediction amd_prediction(const SparseMatrix& B, bool threes) {
  const Eigen::Index n = B.rows();
  if (n % 3 != 0 || !threes) {
    Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> amd;
    amd.cholmod().print = 0;
    amd.cholmod().nmethods = 1;
    amd.cholmod().method[0].ordering = CHOLMOD_AMD;
    amd.analyzePattern(B);
    return {amd.cholmod().fl, amd.cholmod().lnz};
  }
  const Eigen::Index nodes = n / 3;
  std::vector<int> outer(static_cast<size_t>(nodes) + 1, 0), inner;
  std::vector<Eigen::Index> seen(static_cast<size_t>(nodes), -1);
  for (Eigen::Index j = 0; j < nodes; ++j) {
    for (Eigen::Index k = 3 * j; k < 3 * j + 3; ++k)
      for (SparseMatrix::InnerIterator it(B, k); it; ++it) {
        const Eigen::Index node = it.row() / 3;
        if (seen[static_cast<size_t>(node)] == j) continue;
        seen[static_cast<size_t>(node)] = j;
        inner.push_back(static_cast<int>(node));
      }
    if (seen[static_cast<size_t>(j)] != j) inner.push_back(static_cast<int>(j));  // the diagonal
    outer[static_cast<size_t>(j) + 1] = static_cast<int>(inner.size());
  }
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  common.nmethods = 1;
  common.method[0].ordering = CHOLMOD_AMD;
  common.supernodal = CHOLMOD_SIMPLICIAL;  // the column counts are all it needs
  cholmod_sparse graph{};
  graph.nrow = graph.ncol = static_cast<size_t>(nodes);
  graph.nzmax = inner.size();
  graph.p = outer.data();
  graph.i = inner.data();
  graph.stype = -1;  // the lower triangle: every row index >= its column's
  graph.itype = CHOLMOD_INT;
  graph.xtype = CHOLMOD_PATTERN;
  graph.dtype = CHOLMOD_DOUBLE;
  graph.sorted = 0;
  graph.packed = 1;
  cholmod_factor* L = cholmod_analyze(&graph, &common);
  Prediction p;
  if (L != nullptr) {
    const int* count = static_cast<const int*>(L->ColCount);
    for (Eigen::Index j = 0; j < nodes; ++j)
      for (int d = 0; d < 3; ++d) {
        const double c = 3.0 * count[j] - d;
        p.flops += c * c;
        p.entries += c;
      }
    cholmod_free_factor(&L, &common);
  } else {  // CHOLMOD could not (memory): no quick answer, the full analysis decides
    p.flops = p.entries = 0;
  }
  cholmod_finish(&common);
  return p;
}

}  // namespace

namespace {

/// The lower triangle of -A with every diagonal entry present (0 + (-A_kk), or 0 where A
/// has none), column by column in compressed storage; A's columns hold sorted rows.
SparseMatrix negated_lower(const SparseMatrix& A) {
  const Eigen::Index n = A.rows();
  std::vector<int> outer(static_cast<size_t>(n) + 1, 0);
  std::vector<int> inner;
  std::vector<double> values;
  inner.reserve(static_cast<size_t>(A.nonZeros() / 2 + n));
  values.reserve(inner.capacity());
  for (Eigen::Index k = 0; k < n; ++k) {
    inner.push_back(static_cast<int>(k));  // the diagonal, first in its column
    values.push_back(0.0);
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
      if (it.row() < k) continue;
      if (it.row() == k) {
        values.back() = 0.0 + -it.value();  // as the triplets (k, k, 0) and (k, k, -A_kk) summed
      } else {
        inner.push_back(static_cast<int>(it.row()));
        values.push_back(-it.value());
      }
    }
    outer[static_cast<size_t>(k) + 1] = static_cast<int>(inner.size());
  }
  return Eigen::Map<const SparseMatrix>(n, n, static_cast<Eigen::Index>(inner.size()),
                                        outer.data(), inner.data(), values.data());
}

}  // namespace

bool ShiftedCholesky::split(const SparseMatrix& A, SparseMatrix& B) {
  const Eigen::Index n = A.rows();
  std::vector<int> factored, lone;
  std::vector<double> lone_diagonal;
  for (Eigen::Index k = 0; k < n; ++k) {
    double diagonal = 0;
    bool alone = true;
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
      if (it.row() == k)
        diagonal = it.value();
      else
        alone = false;
    }
    if (alone) {
      lone.push_back(static_cast<int>(k));
      lone_diagonal.push_back(diagonal);
    } else {
      factored.push_back(static_cast<int>(k));
    }
  }
  if (lone.empty()) {
    B = negated_lower(A);
    factored.clear();
  } else {
    // A's rows and columns of `factored` (symmetric: a lone row has no entry in them).
    std::vector<int> position(static_cast<size_t>(n), -1);
    for (size_t r = 0; r < factored.size(); ++r) position[static_cast<size_t>(factored[r])] = static_cast<int>(r);
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<size_t>(A.nonZeros()));
    for (const int k : factored)
      for (SparseMatrix::InnerIterator it(A, k); it; ++it)
        entries.emplace_back(position[static_cast<size_t>(it.row())], position[static_cast<size_t>(k)],
                             it.value());
    const auto m = static_cast<Eigen::Index>(factored.size());
    SparseMatrix core(m, m);
    core.setFromTriplets(entries.begin(), entries.end());
    B = negated_lower(core);
  }
  const bool same = n == n_ && factored == factored_ && lone == lone_;
  factored_ = std::move(factored);
  lone_ = std::move(lone);
  lone_diagonal_ = std::move(lone_diagonal);
  return same;
}

ShiftedCholesky::ShiftedCholesky(const SparseMatrix& A, bool cholmod_ordering) : n_(A.rows()) {
  solve_threads_.set_grain(1);  // the two bins of a split solve, one a thread
  split(A, B_);
  llt_.cholmod().print = 0;  // a failed factorisation is an answer, not news
  // Small: AMD alone; CHOLMOD's trial of nested dissection costs more than it saves there.
  if (B_.rows() < kNestedDissectionRows && !cholmod_ordering) {
    cholmod_ordering_ = false;
    llt_.cholmod().nmethods = 1;
    llt_.cholmod().method[0].ordering = CHOLMOD_AMD;
  }
}

void ShiftedCholesky::analyse(double budget) {
  if (analysed_) {
    // Analysed for an earlier caller (a search on a shared pattern): its budget may be lower.
    if (predicted_flops_ > budget)
      throw FactorisationOverBudget(predicted_flops_, predicted_bytes_, budget);
    return;
  }
  if (B_.rows() == 0) {  // every row alone: nothing to factor
    analysed_ = true;
    return;
  }
  {
    const std::lock_guard<std::mutex> turn(cholmod_turn());
    const SerialOpenMp serial;
    if (budget < kNoFactorBudget && B_.rows() > kQuickCheckRows) {
      // (rows in threes are a node's only while no row was left out)
      const Prediction amd = amd_prediction(B_, lone_.empty());
      if (amd.flops > kAmdSlack * budget)
        throw FactorisationOverBudget(amd.flops, 8 * amd.entries, budget, true);
    }
    llt_.analyzePattern(B_);
    analysed_ = true;
    predicted_flops_ = llt_.cholmod().fl;
    predicted_bytes_ = 8 * llt_.cholmod().lnz;
    if (predicted_flops_ > budget)
      throw FactorisationOverBudget(predicted_flops_, predicted_bytes_, budget);
  }
  allocate_values();
}

void ShiftedCholesky::allocate_values() {
  // Outside the turn: this calls only CHOLMOD's allocator, on this object's own common.
  cholmod_factor& L = llt_.factor();
  if (L.xtype != CHOLMOD_PATTERN || !L.is_super) return;
  // What cholmod_super_numeric would do first; it keeps values it finds allocated. Without
  // the memory the factor stays symbolic and the factorisation tries (and reports) again.
  cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, &L, &llt_.cholmod());
  if (L.xtype != CHOLMOD_REAL || L.x == nullptr) return;
  volatile char* x = static_cast<char*>(L.x);  // a write per page maps it
  const size_t bytes = L.xsize * sizeof(double);
  constexpr size_t kPage = 4096;
  for (size_t k = 0; k < bytes; k += kPage) x[k] = 0;
}

void ShiftedCholesky::assign(const SparseMatrix& A) {
  SparseMatrix B;
  const bool same_split = split(A, B);
  const bool same = same_split && B.rows() == B_.rows() && B.nonZeros() == B_.nonZeros() &&
                    std::equal(B.outerIndexPtr(), B.outerIndexPtr() + B.outerSize() + 1,
                               B_.outerIndexPtr()) &&
                    std::equal(B.innerIndexPtr(), B.innerIndexPtr() + B.nonZeros(),
                               B_.innerIndexPtr());
  B_ = std::move(B);
  ok_ = false;
  if (!same) {  // another pattern: analysed anew at the next factor()
    n_ = A.rows();
    analysed_ = false;
    split_ = {};
    split_ready_ = false;
  }
}

bool ShiftedCholesky::factor(double sigma) {
  analyse(kNoFactorBudget);
  ++factorizations;
  sigma_ = sigma;
  // A lone row's pivot is sigma + (-d), positive exactly when sigma > d.
  ok_ = std::all_of(lone_diagonal_.begin(), lone_diagonal_.end(),
                    [&](double d) { return sigma + -d > 0; });
  if (!ok_ || B_.rows() == 0) return ok_;
  const std::lock_guard<std::mutex> turn(cholmod_turn());
  const SerialOpenMp serial;
  llt_.setShift(sigma);
  // The split of the solves (from the factor's pattern, which a numeric factorisation of a
  // factor whose values are allocated reads but does not write: allocate_values) on the
  // solves' second thread while the first factorisation runs.
  const cholmod_factor& L = llt_.factor();
  if (!L.is_super || L.xtype == CHOLMOD_PATTERN) split_ready_ = true;  // serial solves
  solve_threads_.run(split_ready_ ? 1 : 2, [&](int, size_t first, size_t end) {
    for (size_t k = first; k < end; ++k) {
      if (k == 0)
        llt_.factorize(B_);
      else
        split_ = split_supernodes(llt_.factor());
    }
  });
  split_ready_ = true;
  ok_ = llt_.info() == Eigen::Success;
  return ok_;
}

double ShiftedCholesky::proved_above() const {
  if (B_.rows() == 0) return std::nextafter(sigma_, std::numeric_limits<double>::infinity());
  double diagonal = 0;  // as CHOLMOD formed it: sigma + (-A_kk), the first entry of column k
  for (Eigen::Index k = 0; k < B_.rows(); ++k)
    diagonal = std::max(diagonal, std::abs(sigma_ + B_.valuePtr()[B_.outerIndexPtr()[k]]));
  const double delta = cholesky_rounding_bound(llt_.factor(), diagonal);
  return std::nextafter(sigma_ + delta, std::numeric_limits<double>::infinity());
}

void ShiftedCholesky::solve(const double* in, double* out) {
  ++solves;
  if (lone_.empty()) return solve_factored(in, out);
  for (size_t r = 0; r < lone_.size(); ++r) {
    const auto k = static_cast<size_t>(lone_[r]);
    out[k] = in[k] / (sigma_ + -lone_diagonal_[r]);
  }
  if (factored_.empty()) return;
  gathered_in_.resize(factored_.size());
  gathered_out_.resize(factored_.size());
  for (size_t r = 0; r < factored_.size(); ++r) gathered_in_[r] = in[factored_[r]];
  solve_factored(gathered_in_.data(), gathered_out_.data());
  for (size_t r = 0; r < factored_.size(); ++r) out[factored_[r]] = gathered_out_[r];
}

void ShiftedCholesky::solve_factored(const double* in, double* out) {
  const std::lock_guard<std::mutex> turn(cholmod_turn());
  const SerialOpenMp serial;
  if (split_.empty())
    supernodal_solve(llt_.factor(), in, out, solve_work_);
  else
    supernodal_solve_split(llt_.factor(), split_, in, out, solve_work_, solve_threads_);
}

}  // namespace dampbound::detail
