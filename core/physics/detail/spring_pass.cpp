#include "core/physics/detail/spring_pass.hpp"

#include <algorithm>
#include <cmath>

#include "core/physics/detail/spring_batch.hpp"
#include "core/physics/detail/spring_block.hpp"

namespace dampbound::detail {
namespace {

/// |b| summed along row r of a symmetric block, left to right (spring_block.hpp).
inline double row_abs(const double* b, int r) {
  return block_row_abs(b, r, [](double v) { return std::abs(v); });
}

/// Node i's row-sum accumulators: K_ii's upper triangle (6), then the off-diagonal row sums
/// of |A| (3); the anchor adds kappa_a I to K_ii (SPEC 7).
inline void start_rows(const Model& model, size_t i, double* a) {
  const double ka = model.anchor_kappa[i];
  for (int q = 0; q < 9; ++q) a[q] = 0;
  a[0] = a[3] = a[5] = ka;  // element by element: copying a block in stalls store forwarding
}

/// After spring block b: K_ii += B (K_ij = -B), and A_rs = K_rs / sqrt(m_r m_s) adds the
/// spring's row sums of |B| w, `off` (the same at both ends), unless the other node is fixed.
inline void add_block(double* a, const double* b, const double* off, bool other_fixed) {
  for (int q = 0; q < 6; ++q) a[q] = a[q] + b[q];
  if (!other_fixed)
    for (int r = 0; r < 3; ++r) a[6 + r] = a[6 + r] + off[r];
}

/// R_i = the largest of node i's three row sums: the diagonal block's |.| / m_i plus the rest.
inline double row_sum_of(const double* a, double mass) {
  const double r0 = row_abs(a, 0) / mass + a[6];
  const double r1 = row_abs(a, 1) / mass + a[7];
  const double r2 = row_abs(a, 2) / mass + a[8];
  return std::max(std::max(r0, r1), r2);
}

inline Vec3 anchor_force(const Model& model, const std::vector<Vec3>& x, size_t i) {
  return -model.anchor_kappa[i] * (x[i] - model.spec().rest[i]);
}

/// The last spring at node i (its incident springs are listed in increasing index), or -1.
inline long last_spring(const Model& model, size_t i) {
  const int e = model.incident_offset[i + 1];
  if (e == model.incident_offset[i]) return -1;
  const int k = model.incident[static_cast<size_t>(e - 1)];
  return k >= 0 ? k : ~k;
}

/// The pass over the nodes [begin, end): their anchor terms, then every spring with an end
/// among them, in index order, adding its terms to that end only (+f to i, -f to j; B to each
/// free end). A node's sums are thus added in the same order whatever the range, so any split
/// of the nodes gives the same bits; a spring with an end on each side is computed by both
/// sides. Counts the springs whose first node is in the range.
///
/// A node's sums are started when the pass first reaches it (every node before it as well, in
/// order) and its R_i is taken once its last spring is added, so on a mesh numbered along its
/// rows or layers a node's accumulators live in cache for the few rows between the two instead
/// of being written out, read back and written again.
SpringCounts owned_pass(SpringBatchFunction compute, const Model& model,
                        const std::vector<Vec3>& x, std::vector<Vec3>* force,
                        std::vector<double>* row_sum, double* acc, size_t begin, size_t end) {
  const std::vector<std::uint8_t>& fixed = model.spec().fixed;
  SpringCounts counts;
  size_t started = begin;   // the nodes [begin, started) have their sums started
  size_t finished = begin;  // and [begin, finished) their R_i taken
  const auto start_to = [&](size_t i) {  // start every node up to i
    for (; started <= i; ++started) {
      if (force) (*force)[started] = anchor_force(model, x, started);
      if (row_sum) start_rows(model, started, &acc[9 * started]);
    }
  };
  const auto finish_after = [&](long k) {  // R_i of the nodes, in order, whose springs end by k
    if (!row_sum) return;
    for (; finished < started && last_spring(model, finished) <= k; ++finished)
      (*row_sum)[finished] =
          fixed[finished] ? 0.0 : row_sum_of(&acc[9 * finished], model.mass[finished]);
  };
  const bool all = begin == 0 && end == x.size();
  // Only the springs from the first to the last listed at these nodes can reach them: on a
  // mesh numbered along its rows or layers, about this range's share of the list.
  size_t first = 0, last = model.spec().springs.size();
  if (!all) {
    std::swap(first, last);
    for (int e = model.incident_offset[begin]; e < model.incident_offset[end]; ++e) {
      const int k = model.incident[static_cast<size_t>(e)];
      const size_t spring = static_cast<size_t>(k >= 0 ? k : ~k);
      first = std::min(first, spring);
      last = std::max(last, spring + 1);
    }
  }
  // Each batch of springs' directions, forces and blocks in SIMD lanes, then added to the
  // nodes one spring at a time, in index order.
  const SpringBatchInput in = spring_batch_input(model, x);
  SpringBatch batch;
  for (size_t k0 = first; k0 < last; k0 += kSpringBatch) {
    const size_t count = std::min(kSpringBatch, last - k0);
    compute(in, k0, count, force != nullptr, row_sum != nullptr, batch);
    for (size_t q = 0; q < count; ++q) {
      const size_t k = k0 + q;
      const size_t i = static_cast<size_t>(model.spec().springs[k].i);
      const size_t j = static_cast<size_t>(model.spec().springs[k].j);
      const bool own_i = all || (i >= begin && i < end), own_j = all || (j >= begin && j < end);
      if (!own_i && !own_j) continue;
      if (own_i) start_to(i);
      if (own_j) start_to(j);
      if (!batch.direction[q]) {  // zero or NaN length
        counts.zero_length += own_i;
        finish_after(static_cast<long>(k));
        continue;
      }
      if (force) {
        const Vec3 f(batch.force[0][q], batch.force[1][q], batch.force[2][q]);
        if (own_i) (*force)[i] += f;
        if (own_j) (*force)[j] -= f;
      }
      if (row_sum) {
        counts.compressed += own_i && batch.compressed[q];
        const double b[6] = {batch.block[0][q], batch.block[1][q], batch.block[2][q],
                             batch.block[3][q], batch.block[4][q], batch.block[5][q]};
        const double off[3] = {batch.off[0][q], batch.off[1][q], batch.off[2][q]};
        if (own_i && !fixed[i]) add_block(&acc[9 * i], b, off, fixed[j]);
        if (own_j && !fixed[j]) add_block(&acc[9 * j], b, off, fixed[i]);
      }
      finish_after(static_cast<long>(k));
    }
  }
  if (end > begin) start_to(end - 1);
  finish_after(static_cast<long>(model.spec().springs.size()));
  return counts;
}

}  // namespace

SpringBatchFunction spring_batch_for(StepIsa isa) {
  if (isa == StepIsa::best) isa = best_step_isa();
#if defined(__x86_64__)
  if (isa == StepIsa::avx2 && step_isa_supported(StepIsa::avx2)) return spring_batch_avx2::compute;
#endif
  return spring_batch_generic::compute;
}

SpringBatchInput spring_batch_input(const Model& model, const std::vector<Vec3>& x) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "positions are packed x, y, z");
  return {model.spec().springs.data(), model.spring_kappa.data(), model.spring_weight.data(),
          x.empty() ? nullptr : x.front().data()};
}

SpringCounts spring_pass(const Model& model, const std::vector<Vec3>& x,
                         std::vector<Vec3>* force, std::vector<double>* row_sum,
                         SpringPass* pass) {
  const size_t n = x.size(), ns = model.spec().springs.size();
  if (force) force->resize(n);
  if (row_sum) row_sum->resize(n);  // every node's R_i written by its range (0 when fixed)
  std::vector<double> local;
  std::vector<double>& acc = pass ? pass->rows : local;
  const SpringBatchFunction compute = spring_batch_for(pass ? pass->isa : StepIsa::best);
  acc.resize(row_sum ? 9 * n : 0);
  if (!pass || pass->threads.chunks(ns) <= 1)
    return owned_pass(compute, model, x, force, row_sum, acc.data(), 0, n);
  // Threads: the nodes split into as many contiguous ranges as the springs would be (a
  // chunk's work is its springs), each range one owned_pass.
  SpringPass& p = *pass;
  const size_t parts = static_cast<size_t>(p.threads.chunks(ns));
  p.counts.assign(2 * parts, 0);
  p.threads.run(ns, [&](int chunk, size_t, size_t) {
    const size_t c = static_cast<size_t>(chunk);
    const SpringCounts cs =
        owned_pass(compute, model, x, force, row_sum, acc.data(), n * c / parts,
                   n * (c + 1) / parts);
    p.counts[2 * c] = cs.zero_length;
    p.counts[2 * c + 1] = cs.compressed;
  });
  SpringCounts counts;
  for (size_t c = 0; c < parts; ++c) {
    counts.zero_length += p.counts[2 * c];
    counts.compressed += p.counts[2 * c + 1];
  }
  return counts;
}

}  // namespace dampbound::detail
