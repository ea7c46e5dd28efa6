#include "core/analysis/detail/supernodal_solve.hpp"

#include <cholmod.h>

#include <algorithm>
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

/// L's supernode s, forward: its triangle solved in place in ys (= y + k1), its columns'
/// products with the rows below them into e (the caller subtracts them from those rows).
inline void forward_block(const Supernode& sn, double* ys, double* e, bool blas) {
  const int columns = sn.columns, height = sn.height, below = sn.below;
  const double* Ls = sn.values;
  if (blas) {
    const int one = 1;
    const double plus = 1, zero = 0;
    dtrsv_("L", "N", "N", &columns, Ls, &height, ys, &one);
    if (below > 0)
      dgemv_("N", &below, &columns, &plus, Ls + columns, &height, ys, &one, &zero, e, &one);
    return;
  }
  for (int t = 0; t < below; ++t) e[t] = 0;
  for (int j = 0; j < columns; ++j) {
    const double* col = Ls + static_cast<size_t>(j) * static_cast<size_t>(height);
    const double yj = ys[j] / col[j];
    ys[j] = yj;
    for (int i = j + 1; i < columns; ++i) ys[i] -= col[i] * yj;
    for (int t = 0; t < below; ++t) e[t] += col[columns + t] * yj;
  }
}

/// L's supernode s, backward (L^T): e holds y at the rows below its columns; its triangle
/// solved in place in ys from its last column to its first.
inline void backward_block(const Supernode& sn, double* ys, const double* e, bool blas) {
  const int columns = sn.columns, height = sn.height, below = sn.below;
  const double* Ls = sn.values;
  if (blas) {
    const int one = 1;
    const double minus = -1, plus = 1;
    if (below > 0)
      dgemv_("T", &below, &columns, &minus, Ls + columns, &height, e, &one, &plus, ys, &one);
    dtrsv_("L", "T", "N", &columns, Ls, &height, ys, &one);
    return;
  }
  for (int j = columns - 1; j >= 0; --j) {
    const double* col = Ls + static_cast<size_t>(j) * static_cast<size_t>(height);
    const double sum = dot(col + columns, e, below) + dot(col + j + 1, ys + j + 1, columns - j - 1);
    ys[j] = (ys[j] - sum) / col[j];
  }
}

void check_factor(const cholmod_factor_struct& L) {
  if (!L.is_super || !L.is_ll || L.itype != CHOLMOD_INT || L.xtype != CHOLMOD_REAL ||
      L.dtype != CHOLMOD_DOUBLE || L.minor < L.n)
    throw std::invalid_argument("supernodal_solve: not a successful real supernodal LL' factor");
}

}  // namespace

void supernodal_solve(const cholmod_factor_struct& L, const double* b, double* x,
                      std::vector<double>& work) {
  check_factor(L);
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
    forward_block(sn, y + sn.k1, e, sn.columns >= kBlasColumns);
    for (int t = 0; t < sn.below; ++t) y[sn.below_rows[t]] -= e[t];
  }
  // L^T x = y': backwards, each supernode's columns first take the rows below (gathered in
  // e), then its triangle from its last column to its first.
  for (size_t s = L.nsuper; s-- > 0;) {
    const Supernode sn(L, s);
    for (int t = 0; t < sn.below; ++t) e[t] = y[sn.below_rows[t]];
    backward_block(sn, y + sn.k1, e, sn.columns >= kBlasColumns);
  }
  for (size_t i = 0; i < n; ++i) x[perm[i]] = y[i];
}

SolveSplit split_supernodes(const cholmod_factor_struct& L, std::size_t min_entries) {
  SolveSplit split;
  if (!L.is_super || L.itype != CHOLMOD_INT || L.xsize < min_entries) return split;
  const size_t ns = L.nsuper;
  const int* super = static_cast<const int*>(L.super);
  const int* pi = static_cast<const int*>(L.pi);
  const int* rows = static_cast<const int*>(L.s);
  std::vector<int> column_owner(L.n);
  for (size_t s = 0; s < ns; ++s)
    for (int c = super[s]; c < super[s + 1]; ++c)
      column_owner[static_cast<size_t>(c)] = static_cast<int>(s);
  // The elimination tree of the supernodes: the parent owns the first row below the columns.
  std::vector<int> parent(ns, -1), first(ns);
  std::vector<double> work(ns);  // a subtree's entries: what its solves read
  std::vector<std::vector<int>> children(ns);
  for (size_t s = 0; s < ns; ++s) {
    const int columns = super[s + 1] - super[s], height = pi[s + 1] - pi[s];
    work[s] += static_cast<double>(columns) * height;
    if (height > columns) {
      const int p = column_owner[static_cast<size_t>(rows[pi[s] + columns])];
      if (p <= static_cast<int>(s)) return {};  // not in postorder: serial solves
      parent[s] = p;
      children[static_cast<size_t>(p)].push_back(static_cast<int>(s));
    }
  }
  // Postorder: every subtree is the run [first, root]; check it, and sum the work up.
  std::vector<int> count(ns, 1);
  for (size_t s = 0; s < ns; ++s) {
    first[s] = static_cast<int>(s);
    for (int c : children[s]) first[s] = std::min(first[s], first[static_cast<size_t>(c)]);
  }
  for (size_t s = 0; s < ns; ++s) {
    if (parent[s] >= 0) {
      count[static_cast<size_t>(parent[s])] += count[s];
      work[static_cast<size_t>(parent[s])] += work[s];
    }
  }
  for (size_t s = 0; s < ns; ++s)
    if (static_cast<int>(s) - first[s] + 1 != count[s]) return {};
  double total = 0;
  std::vector<int> frontier;
  for (size_t s = 0; s < ns; ++s)
    if (parent[s] < 0) {
      frontier.push_back(static_cast<int>(s));
      total += work[s];
    }
  // Take the heaviest subtree apart (its root to the top, its children to the frontier) while
  // that lowers the top plus the heavier bin. Bins are filled heaviest subtree first, each to
  // the lighter bin (the longest-processing-time rule); subtrees under 1/256 of the work, in
  // order, last.
  const double small = total / 256;
  const auto assign = [&](const std::vector<int>& f, std::vector<int>* bin_of) {
    std::vector<size_t> big;
    double rest = 0;
    for (size_t k = 0; k < f.size(); ++k) {
      if (work[static_cast<size_t>(f[k])] >= small)
        big.push_back(k);
      else
        rest += work[static_cast<size_t>(f[k])];
    }
    std::stable_sort(big.begin(), big.end(), [&](size_t a, size_t b) {
      return work[static_cast<size_t>(f[a])] > work[static_cast<size_t>(f[b])];
    });
    double load[2] = {0, 0};
    if (bin_of) bin_of->assign(f.size(), -1);
    for (size_t k : big) {
      const int b = load[1] < load[0] ? 1 : 0;
      load[b] += work[static_cast<size_t>(f[k])];
      if (bin_of) (*bin_of)[k] = b;
    }
    if (!bin_of)  // the small ones fill the lighter bin, then both
      return std::max({load[0], load[1], 0.5 * (load[0] + load[1] + rest)});
    for (size_t k = 0; k < f.size(); ++k)
      if ((*bin_of)[k] < 0) {
        const int b = load[1] < load[0] ? 1 : 0;
        load[b] += work[static_cast<size_t>(f[k])];
        (*bin_of)[k] = b;
      }
    return std::max(load[0], load[1]);
  };
  std::vector<int> top, best_frontier = frontier, best_top;
  double top_work = 0, best = assign(frontier, nullptr);
  for (int round = 0; round < kSplitRounds && !frontier.empty(); ++round) {
    const auto heaviest = std::max_element(frontier.begin(), frontier.end(), [&](int a, int b) {
      return work[static_cast<size_t>(a)] < work[static_cast<size_t>(b)];
    });
    const int s = *heaviest;
    if (work[static_cast<size_t>(s)] < total / 8) break;  // the bins balance already
    frontier.erase(heaviest);
    top.push_back(s);
    top_work += work[static_cast<size_t>(s)];
    for (int c : children[static_cast<size_t>(s)]) {
      frontier.push_back(c);
      top_work -= work[static_cast<size_t>(c)];
    }
    const double cost = top_work + assign(frontier, nullptr);
    if (cost < best) {
      best = cost;
      best_frontier = frontier;
      best_top = top;
    }
  }
  if (best >= kSplitWorthIt * total) return {};  // no split worth a thread
  // Bin 1's supernodes run the loops, not BLAS: where the bins' wide ones hold much of the work
  // (a 3-D mesh's separators), the loops cost more than the second thread gains.
  double wide = 0;
  {
    std::vector<char> in_top(ns, 0);
    for (int t : best_top) in_top[static_cast<size_t>(t)] = 1;
    for (size_t q = 0; q < ns; ++q) {
      const int columns = super[q + 1] - super[q];
      if (!in_top[q] && columns >= kBlasColumns)
        wide += static_cast<double>(columns) * (pi[q + 1] - pi[q]);
    }
  }
  if (wide > kSplitWideShare * total) return {};
  std::vector<int> bin_of;
  assign(best_frontier, &bin_of);
  for (size_t k = 0; k < best_frontier.size(); ++k) {
    const int root = best_frontier[k];
    split.bins[bin_of[k]].push_back({first[static_cast<size_t>(root)], root});
  }
  for (auto& bin : split.bins) std::sort(bin.begin(), bin.end());
  split.top = best_top;
  std::sort(split.top.begin(), split.top.end());
  split.top_index.assign(L.n, -1);
  for (int s : split.top)
    for (int c = super[s]; c < super[s + 1]; ++c) {
      split.top_index[static_cast<size_t>(c)] = static_cast<int>(split.top_rows.size());
      split.top_rows.push_back(c);
    }
  return split;
}

void supernodal_solve_split(const cholmod_factor_struct& L, const SolveSplit& split,
                            const double* b, double* x, std::vector<double>& work,
                            NodeThreads& threads) {
  check_factor(L);
  const size_t n = L.n, m = split.top_rows.size(), esize = L.maxesize;
  const int* perm = static_cast<const int*>(L.Perm);
  work.resize(n + 2 * esize + 2 * m);
  double* y = work.data();
  double* e[2] = {y + n, y + n + esize};
  double* gathered[2] = {y + n + 2 * esize,
                         y + n + 2 * esize + m};  // each bin's terms for the top's rows
  for (size_t i = 0; i < n; ++i) y[i] = b[perm[i]];
  for (double* g : gathered) std::fill(g, g + m, 0.0);
  const int* top_index = split.top_index.data();
  // Forward: the bins at once (BLAS in bin 0 only); each writes its own subtrees' rows and
  // gathers its terms for the top's rows; then those, bin 0's first, and the top's supernodes.
  threads.run(2, [&](int, size_t first_bin, size_t end_bin) {
    for (size_t bin = first_bin; bin < end_bin; ++bin) {
      double* eb = e[bin];
      double* g = gathered[bin];
      for (const auto& [from, to] : split.bins[bin])
        for (int s = from; s <= to; ++s) {
          const Supernode sn(L, static_cast<size_t>(s));
          forward_block(sn, y + sn.k1, eb, bin == 0 && sn.columns >= kBlasColumns);
          for (int t = 0; t < sn.below; ++t) {
            const int r = sn.below_rows[t];
            const int q = top_index[r];
            if (q < 0)
              y[r] -= eb[t];
            else
              g[q] += eb[t];
          }
        }
    }
  });
  for (size_t q = 0; q < m; ++q) {
    double& yr = y[split.top_rows[q]];
    yr -= gathered[0][q];
    yr -= gathered[1][q];
  }
  for (int s : split.top) {
    const Supernode sn(L, static_cast<size_t>(s));
    forward_block(sn, y + sn.k1, e[0], sn.columns >= kBlasColumns);
    for (int t = 0; t < sn.below; ++t) y[sn.below_rows[t]] -= e[0][t];
  }
  // Backward: the top's supernodes (they read only the top's rows), then the bins at once
  // (each reads the top's rows and its own).
  for (auto it = split.top.rbegin(); it != split.top.rend(); ++it) {
    const Supernode sn(L, static_cast<size_t>(*it));
    for (int t = 0; t < sn.below; ++t) e[0][t] = y[sn.below_rows[t]];
    backward_block(sn, y + sn.k1, e[0], sn.columns >= kBlasColumns);
  }
  threads.run(2, [&](int, size_t first_bin, size_t end_bin) {
    for (size_t bin = first_bin; bin < end_bin; ++bin) {
      double* eb = e[bin];
      const auto& runs = split.bins[bin];
      for (auto it = runs.rbegin(); it != runs.rend(); ++it)
        for (int s = it->second; s >= it->first; --s) {
          const Supernode sn(L, static_cast<size_t>(s));
          for (int t = 0; t < sn.below; ++t) eb[t] = y[sn.below_rows[t]];
          backward_block(sn, y + sn.k1, eb, bin == 0 && sn.columns >= kBlasColumns);
        }
    }
  });
  for (size_t i = 0; i < n; ++i) x[perm[i]] = y[i];
}

}  // namespace dampbound::detail
