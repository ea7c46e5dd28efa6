// clang-format off
#include "core/analysis/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/linear_stability.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/detail/spring_block.hpp"
#include "core/node_threads.hpp"

namespace dampbound {

std::vector<int> free_blocks(const Model& model, int* free_count) {
  std::vector<int> block(model.rest.size(), -1);
  int count = 0;
  for (size_t i = 0; i < block.size(); ++i)
    if (!model.fixed[i]) block[i] = count++;
  if (free_count) *free_count = count;
  return block;
}

SparseMatrix tangent_stiffness(const Model& model, const std::vector<Vec3>& x,
                               bool clamp_compression, int threads) {
  int nfree = 0;
  const std::vector<int> block = free_blocks(model, &nfree);
  NodeThreads pool(threads);
  // Each spring's block B once (upper triangle); springs of no direction have none (SPEC 1).
  const size_t ns = model.springs.size();
  std::vector<double> spring_block(6 * ns);
  std::vector<std::uint8_t> directed(ns, 0);
  pool.run(ns, [&](int, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const Spring& s = model.springs[k];
      const Vec3 delta = x[static_cast<size_t>(s.j)] - x[static_cast<size_t>(s.i)];
      const double l = delta.norm();
      if (!(l > 0)) continue;
      const Vec3 d = delta / l;
      const double ratio = s.rest_length / l;
      double tension = 1.0 - ratio;  // (1 - l0/l)
      if (clamp_compression) tension = std::max(0.0, tension);
      spring_tangent_block(model.spring_kappa[k], tension, ratio, d.data(), &spring_block[6 * k]);
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
  const size_t nodes = model.rest.size();
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
        const Spring& s = model.springs[spring];
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
  for (size_t i = 0; i < model.rest.size(); ++i)
    if (!model.fixed[i])
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

std::optional<double> psd_floor(const Model& model, const std::vector<Vec3>& x,
                                bool clamp_compression) {
  double floor = std::numeric_limits<double>::infinity();
  double m_min = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < model.rest.size(); ++i)
    if (!model.fixed[i]) {
      floor = std::min(floor, model.anchor_kappa[i] / model.mass[i]);
      m_min = std::min(m_min, model.mass[i]);
    }
  if (!std::isfinite(floor)) return std::nullopt;  // no free node
  // The negative part a rounding-short spring adds, kappa |1 - l0/l| (I - d d^T), has
  // absolute row sums below 2 per 3x3 block, twice per row (diagonal and off-diagonal
  // block), divided by sqrt(m_i m_j) >= m_min: per node at most 4 sum kappa |t| / m_min.
  std::vector<double> deficit(model.rest.size(), 0.0);
  for (size_t k = 0; k < model.springs.size(); ++k) {
    const Spring& s = model.springs[k];
    const double l = (x[static_cast<size_t>(s.j)] - x[static_cast<size_t>(s.i)]).norm();
    if (!(l > 0)) continue;  // skipped by tangent_stiffness too
    const double tension = 1.0 - s.rest_length / l;
    if (clamp_compression || tension >= 0) continue;
    if (tension < -1e-12) return std::nullopt;  // truly compressed: B may be indefinite
    deficit[static_cast<size_t>(s.i)] += model.spring_kappa[k] * -tension;
    deficit[static_cast<size_t>(s.j)] += model.spring_kappa[k] * -tension;
  }
  const double worst = deficit.empty() ? 0 : *std::max_element(deficit.begin(), deficit.end());
  return floor - 4 * worst / m_min;
}

bool positive_spring_block(const Model& model, const std::vector<Vec3>& x, size_t k,
                           Eigen::Matrix3d& B) {
  const Spring& s = model.springs[k];
  const size_t i = static_cast<size_t>(s.i), j = static_cast<size_t>(s.j);
  const Vec3 e = x[j] - x[i];
  const double l = e.norm();
  if (!(l > 0) || i == j) return false;  // no direction (SPEC 1), or no part in K
  const double d[3] = {e.x() / l, e.y() / l, e.z() / l};
  const double ratio = s.rest_length / l, tension = 1.0 - ratio;
  // B+ = B where B >= 0; compressed (tension < 0), its part along d alone: kappa d d^T.
  double b[6];
  spring_tangent_block(model.spring_kappa[k], std::max(tension, 0.0), tension >= 0 ? ratio : 1.0,
                       d, b);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) B(r, c) = b[sym3(r, c)];
  return true;
}

void splitting_ceilings(const Model& model, const std::vector<Vec3>& x,
                        std::vector<double>& ceiling) {
  const size_t n = model.rest.size();
  std::vector<Eigen::Matrix3d> D(n, Eigen::Matrix3d::Zero());
  Eigen::Matrix3d B;
  for (size_t k = 0; k < model.springs.size(); ++k) {
    if (!positive_spring_block(model, x, k, B)) continue;
    const size_t i = static_cast<size_t>(model.springs[k].i);
    const size_t j = static_cast<size_t>(model.springs[k].j);
    const bool both = !model.fixed[i] && !model.fixed[j];
    if (!model.fixed[i]) D[i] += both ? 2 * B : B;
    if (!model.fixed[j]) D[j] += both ? 2 * B : B;
  }
  ceiling.assign(n, 0.0);
  double largest_trace = 0;
  for (size_t i = 0; i < n; ++i) {
    if (model.fixed[i]) continue;
    D[i].diagonal().array() += model.anchor_kappa[i];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(D[i], Eigen::EigenvaluesOnly);
    ceiling[i] = es.eigenvalues()(2) / model.mass[i];
    largest_trace = std::max(largest_trace, D[i].trace() / model.mass[i]);
  }
  for (size_t i = 0; i < n; ++i)
    if (!model.fixed[i]) ceiling[i] += 1e-12 * largest_trace;
}

double largest_eigenvalue(const SparseMatrix& A) { return certified_largest_eigenvalue(A).hi; }
double smallest_eigenvalue_above(const SparseMatrix& A, double floor) {
  const Eigen::Index n = A.rows();
  if (n == 0) return 0;
  if (n <= 300) {  // small: dense is cheap and finds every zero mode
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(A), Eigen::EigenvaluesOnly};
    for (Eigen::Index k = 0; k < n; ++k)
      if (es.eigenvalues()(k) > floor) return es.eigenvalues()(k);
    return std::numeric_limits<double>::quiet_NaN();
  }
  // Large: the 12 smallest by Lanczos (a free mesh has 6 rigid modes; 12 leaves room).
  Spectra::SparseSymMatProd<double> op(A);
  const Eigen::Index nev = std::min<Eigen::Index>(12, n - 2);
  Spectra::SymEigsSolver<Spectra::SparseSymMatProd<double>> eigs(op, nev, std::min<Eigen::Index>(n, 96));
  eigs.init();
  eigs.compute(Spectra::SortRule::SmallestAlge, 5000, 1e-11, Spectra::SortRule::SmallestAlge);
  if (eigs.info() != Spectra::CompInfo::Successful) return std::numeric_limits<double>::quiet_NaN();
  for (Eigen::Index k = 0; k < eigs.eigenvalues().size(); ++k)
    if (eigs.eigenvalues()(k) > floor) return eigs.eigenvalues()(k);
  return std::numeric_limits<double>::quiet_NaN();
}

double largest_eigenpair(const SparseMatrix& A, Eigen::VectorXd& vector, int threads,
                         double max_factor_flops) {
  return certified_largest_eigenvalue(A, &vector, threads, max_factor_flops).hi;
}
double smallest_eigenvalue(const SparseMatrix& A) { return certified_smallest_eigenvalue(A).lo; }

double max_stiffness_eigenvalue(const Model& model, const std::vector<Vec3>& x) {
  return largest_eigenvalue(mass_weighted(model, tangent_stiffness(model, x)));
}

StiffnessSpectrum stiffness_spectrum(const Model& model, const std::vector<Vec3>& x) {
  const CertifiedSpectrum ends =
      certified_spectrum(mass_weighted(model, tangent_stiffness(model, x)), psd_floor(model, x));
  return {ends.smallest.lo, ends.largest.hi};
}

bool spec7_unstable(double lambda_max, double c, double dt) {
  const double c_dt = c * dt;
  return !(c_dt < 2) || !(lambda_max * dt * dt < 4 - 2 * c_dt);
}

double spec7_gamma_max(double lambda_max, double m, double dt) {
  // lambda dt^2 < 4 - 2 c dt, c = gamma/m  =>  gamma < 2m/dt - m lambda dt / 2.
  return 2.0 * m / dt - m * lambda_max * dt / 2.0;
}

double spec7_dt_max_undamped(double lambda_max) {
  return lambda_max > 0 ? 2.0 / std::sqrt(lambda_max) : std::numeric_limits<double>::infinity();
}

LinearLimits linear_limits(double lambda_max, double m, double dt) {
  LinearLimits l;
  l.lambda_max = lambda_max;
  l.gamma_max = spec7_gamma_max(lambda_max, m, dt);
  l.dt_max_undamped = spec7_dt_max_undamped(lambda_max);
  return l;
}

double semi_implicit_dt_max(double lambda_max, double c) {
  // lambda dt^2 + 2 c dt - 4 = 0, the positive root; dt < 2/c when lambda = 0.
  if (!(lambda_max > 0)) return c > 0 ? 2.0 / c : std::numeric_limits<double>::infinity();
  return (std::sqrt(c * c + 4.0 * lambda_max) - c) / lambda_max;
}

double semi_implicit_stability_index(const Model& model, const SparseMatrix& K_weighted,
                                     const std::vector<double>& gamma, double dt) {
  SparseMatrix S = (dt * dt) * K_weighted;
  std::vector<Eigen::Triplet<double>> diag;
  int b = 0;
  for (size_t i = 0; i < model.rest.size(); ++i) {
    if (model.fixed[i]) continue;
    for (int r = 0; r < 3; ++r) diag.emplace_back(3 * b + r, 3 * b + r, 2.0 * dt * gamma[i] / model.mass[i]);
    ++b;
  }
  SparseMatrix D(S.rows(), S.cols());
  D.setFromTriplets(diag.begin(), diag.end());
  S += D;
  return largest_eigenvalue(S);
}

}  // namespace dampbound
