#include "dampbound/physics/stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/physics/detail/spring_block.hpp"
#include "dampbound/physics/node_threads.hpp"

namespace dampbound {

std::vector<int> free_blocks(const Model& model, int* free_count) {
  std::vector<int> block(model.spec().rest.size(), -1);
  int count = 0;
  for (size_t i = 0; i < block.size(); ++i)
    if (!model.spec().fixed[i]) block[i] = count++;
  if (free_count) *free_count = count;
  return block;
}

SparseMatrix tangent_stiffness(const Model& model, const std::vector<Vec3>& x,
                               bool clamp_compression, int threads) {
  int nfree = 0;
  const std::vector<int> block = free_blocks(model, &nfree);
  NodeThreads pool(threads);
  // Each spring's block B once (upper triangle); springs of no direction have none (SPEC 1).
  const size_t ns = model.spec().springs.size();
  std::vector<double> spring_block(6 * ns);
  std::vector<std::uint8_t> directed(ns, 0);
  pool.run(ns, [&](int, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const Spring& s = model.spec().springs[k];
      const SpringGeometry g = spring_geometry(x[static_cast<size_t>(s.i)].data(),
                                                       x[static_cast<size_t>(s.j)].data(), s.rest_length);
      if (!(g.length > 0)) continue;
      const double tension = clamp_compression ? std::max(0.0, g.tension) : g.tension;
      spring_tangent_block(model.spring_kappa[k], tension, g.ratio, g.d, &spring_block[6 * k]);
      directed[k] = 1;
    }
  });
  // K row by row, straight into compressed storage: node i's rows hold its anchor and its
  // springs (Model::incident, in index order) on the diagonal block, and -B at each free
  // neighbour's block. An entry exists when some term of it is not zero, and its terms are
  // added in the order "anchors, then springs by index" (what setFromTriplets of that triplet
  // list gives, bit for bit: tests/core/analysis/linear_stability_test.cpp keeps it as the
  // reference). K is symmetric in pattern and values, so its rows are its columns. No
  // triplet list: 248M of them (4 GB) for a 1M-node tetrahedral block. The nodes are taken in
  // contiguous ranges on the threads, each range's rows into arrays of its own, then copied
  // into place: every entry is the same bits on any thread count.
  struct Column {
    int block;
    double value[9];
    bool present[9];
  };
  struct Rows {
    std::vector<int> ends;  // each row's end in inner and values
    std::vector<int> inner;
    std::vector<double> values;
  };
  const size_t nodes = model.spec().rest.size();
  std::vector<Rows> parts(static_cast<size_t>(pool.chunks(nodes)));
  auto add = [](Column& c, int q, double v) {
    if (v == 0) return;  // a zero term adds no entry (as the triplet list skipped it)
    c.value[q] = c.present[q] ? c.value[q] + v : v;
    c.present[q] = true;
  };
  pool.run(nodes, [&](int chunk, size_t begin, size_t end) {
    Rows& part = parts[static_cast<size_t>(chunk)];
    // At most 3 entries per row for the node itself and for each incident spring (reserved
    // once: growing 1.6 GB of arrays would copy them again).
    const size_t incident =
        static_cast<size_t>(model.incident_offset[end] - model.incident_offset[begin]);
    part.inner.reserve(9 * (incident + (end - begin)));
    part.values.reserve(part.inner.capacity());
    std::vector<Column> row_blocks;
    for (size_t i = begin; i < end; ++i) {
      const int bi = block[i];
      if (bi < 0) continue;
      row_blocks.clear();
      row_blocks.push_back(Column{bi, {}, {}});
      if (model.anchor_kappa[i] > 0)
        for (int r = 0; r < 3; ++r) add(row_blocks[0], 4 * r, model.anchor_kappa[i]);
      for (int e = model.incident_offset[i]; e < model.incident_offset[i + 1]; ++e) {
        const int k = model.incident[static_cast<size_t>(e)];
        const size_t spring = static_cast<size_t>(k >= 0 ? k : ~k);
        if (!directed[spring]) continue;
        const double* b = &spring_block[6 * spring];
        for (int q = 0; q < 9; ++q) add(row_blocks[0], q, b[sym3(q / 3, q % 3)]);
        const Spring& s = model.spec().springs[spring];
        const int bj = block[static_cast<size_t>(k >= 0 ? s.j : s.i)];
        if (bj < 0) continue;
        auto it = std::find_if(row_blocks.begin() + 1, row_blocks.end(),
                               [bj](const Column& c) { return c.block == bj; });
        if (it == row_blocks.end()) {
          row_blocks.push_back(Column{bj, {}, {}});
          it = row_blocks.end() - 1;
        }
        for (int q = 0; q < 9; ++q) add(*it, q, -b[sym3(q / 3, q % 3)]);
      }
      std::sort(row_blocks.begin(), row_blocks.end(),
                [](const Column& a, const Column& b) { return a.block < b.block; });
      for (int r = 0; r < 3; ++r) {
        for (const Column& c : row_blocks)
          for (int col = 0; col < 3; ++col)
            if (c.present[3 * r + col]) {
              part.inner.push_back(3 * c.block + col);
              part.values.push_back(c.value[3 * r + col]);
            }
        part.ends.push_back(static_cast<int>(part.inner.size()));
      }
    }
  });
  std::vector<size_t> first_row(parts.size() + 1, 0), first_entry(parts.size() + 1, 0);
  for (size_t c = 0; c < parts.size(); ++c) {
    first_row[c + 1] = first_row[c] + parts[c].ends.size();
    first_entry[c + 1] = first_entry[c] + parts[c].inner.size();
  }
  SparseMatrix K(3 * nfree, 3 * nfree);
  K.resizeNonZeros(static_cast<Eigen::Index>(first_entry.back()));
  K.outerIndexPtr()[0] = 0;
  pool.run(nodes, [&](int chunk, size_t, size_t) {  // the same ranges: one part each
    const size_t c = static_cast<size_t>(chunk);
    const Rows& part = parts[c];
    const int offset = static_cast<int>(first_entry[c]);
    for (size_t r = 0; r < part.ends.size(); ++r)
      K.outerIndexPtr()[first_row[c] + r + 1] = offset + part.ends[r];
    std::copy(part.inner.begin(), part.inner.end(), K.innerIndexPtr() + first_entry[c]);
    std::copy(part.values.begin(), part.values.end(), K.valuePtr() + first_entry[c]);
  });
  return K;
}

SparseMatrix mass_weighted(const Model& model, const SparseMatrix& K, int threads) {
  return mass_weighted(model, SparseMatrix(K), threads);
}

SparseMatrix mass_weighted(const Model& model, SparseMatrix&& K, int threads) {
  std::vector<double> inv_sqrt_m;
  for (size_t i = 0; i < model.spec().rest.size(); ++i)
    if (!model.spec().fixed[i])
      for (int r = 0; r < 3; ++r) inv_sqrt_m.push_back(1.0 / std::sqrt(model.mass[i]));
  SparseMatrix A = std::move(K);
  NodeThreads(threads).run(static_cast<size_t>(A.outerSize()), [&](int, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k)
      for (SparseMatrix::InnerIterator it(A, static_cast<Eigen::Index>(k)); it; ++it)
        it.valueRef() *=
            inv_sqrt_m[static_cast<size_t>(it.row())] * inv_sqrt_m[static_cast<size_t>(it.col())];
  });
  return A;
}

SparseMatrix spring_damping_matrix(const Model& model, const std::vector<Vec3>& x,
                                   bool clamp_compression) {
  int nfree = 0;
  const std::vector<int> block = free_blocks(model, &nfree);
  std::vector<Eigen::Triplet<double>> t;
  const double alpha = model.rayleigh_mass, beta = model.rayleigh_stiffness;
  for (size_t i = 0; i < model.spec().rest.size(); ++i) {
    const int b = block[i];
    if (b < 0) continue;
    const double diag = alpha * model.mass[i] + beta * model.anchor_kappa[i] + model.anchor_kd[i];
    if (diag != 0)
      for (int r = 0; r < 3; ++r) t.emplace_back(3 * b + r, 3 * b + r, diag);
  }
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    const Spring& s = model.spec().springs[k];
    const SpringGeometry g = spring_geometry(x[static_cast<size_t>(s.i)].data(),
                                                     x[static_cast<size_t>(s.j)].data(), s.rest_length);
    if (!(g.length > 0)) continue;
    const Vec3 d(g.d[0], g.d[1], g.d[2]);
    const double ratio = g.ratio;
    const double tension = clamp_compression ? std::max(0.0, g.tension) : g.tension;
    const double kappa = model.spring_kappa[k], kd = model.spring_kd[k];
    // beta B + kd P = (beta kappa ratio + kd) d d^T + beta kappa tension I
    const Eigen::Matrix3d E = (beta * kappa * ratio + kd) * (d * d.transpose()) +
                              (beta * kappa * tension) * Eigen::Matrix3d::Identity();
    const int bi = block[static_cast<size_t>(s.i)], bj = block[static_cast<size_t>(s.j)];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const double e = E(r, c);
        if (e == 0) continue;
        if (bi >= 0) t.emplace_back(3 * bi + r, 3 * bi + c, e);
        if (bj >= 0) t.emplace_back(3 * bj + r, 3 * bj + c, e);
        if (bi >= 0 && bj >= 0) {
          t.emplace_back(3 * bi + r, 3 * bj + c, -e);
          t.emplace_back(3 * bj + r, 3 * bi + c, -e);
        }
      }
  }
  SparseMatrix C(3 * nfree, 3 * nfree);
  C.setFromTriplets(t.begin(), t.end());
  return C;
}

SparseMatrix weighted_damping(const Model& model, const std::vector<Vec3>& x,
                              const std::vector<double>& gamma) {
  SparseMatrix C = spring_damping_matrix(model, x);
  int nfree = 0;
  const std::vector<int> block = free_blocks(model, &nfree);
  Eigen::VectorXd w(3 * nfree);
  std::vector<Eigen::Triplet<double>> g;
  for (size_t i = 0; i < model.spec().rest.size(); ++i) {
    const int b = block[i];
    if (b < 0) continue;
    for (int r = 0; r < 3; ++r) {
      w(3 * b + r) = 1.0 / std::sqrt(model.mass[i]);
      if (gamma[i] != 0) g.emplace_back(3 * b + r, 3 * b + r, gamma[i]);
    }
  }
  SparseMatrix G(3 * nfree, 3 * nfree);
  G.setFromTriplets(g.begin(), g.end());
  C += G;
  return w.asDiagonal() * C * w.asDiagonal();
}

}  // namespace dampbound
