// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "dampbound/analysis/linear_stability.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/physics/detail/spring_block.hpp"
#include "dampbound/physics/node_threads.hpp"

namespace dampbound {

std::optional<double> psd_floor(const Model& model, const std::vector<Vec3>& x,
                                bool clamp_compression) {
  double floor = std::numeric_limits<double>::infinity();
  double m_min = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < model.spec().rest.size(); ++i)
    if (!model.spec().fixed[i]) {
      floor = std::min(floor, model.anchor_kappa[i] / model.mass[i]);
      m_min = std::min(m_min, model.mass[i]);
    }
  if (!std::isfinite(floor)) return std::nullopt;  // no free node
  // The negative part a rounding-short spring adds, kappa |1 - l0/l| (I - d d^T), has
  // absolute row sums below 2 per 3x3 block, twice per row (diagonal and off-diagonal
  // block), divided by sqrt(m_i m_j) >= m_min: per node at most 4 sum kappa |t| / m_min.
  std::vector<double> deficit(model.spec().rest.size(), 0.0);
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    const Spring& s = model.spec().springs[k];
    const SpringGeometry g = spring_geometry(x[static_cast<size_t>(s.i)].data(),
                                                     x[static_cast<size_t>(s.j)].data(), s.rest_length);
    if (!(g.length > 0)) continue;  // skipped by tangent_stiffness too
    const double tension = g.tension;
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
  const Spring& s = model.spec().springs[k];
  const size_t i = static_cast<size_t>(s.i), j = static_cast<size_t>(s.j);
  const SpringGeometry g = spring_geometry(x[i].data(), x[j].data(), s.rest_length);
  if (!(g.length > 0) || i == j) return false;  // no direction (SPEC 1), or no part in K
  const double* d = g.d;
  const double ratio = g.ratio, tension = g.tension;
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
  const size_t n = model.spec().rest.size();
  std::vector<Eigen::Matrix3d> D(n, Eigen::Matrix3d::Zero());
  Eigen::Matrix3d B;
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    if (!positive_spring_block(model, x, k, B)) continue;
    const size_t i = static_cast<size_t>(model.spec().springs[k].i);
    const size_t j = static_cast<size_t>(model.spec().springs[k].j);
    const bool both = !model.spec().fixed[i] && !model.spec().fixed[j];
    if (!model.spec().fixed[i]) D[i] += both ? 2 * B : B;
    if (!model.spec().fixed[j]) D[j] += both ? 2 * B : B;
  }
  ceiling.assign(n, 0.0);
  double largest_trace = 0;
  for (size_t i = 0; i < n; ++i) {
    if (model.spec().fixed[i]) continue;
    D[i].diagonal().array() += model.anchor_kappa[i];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(D[i], Eigen::EigenvaluesOnly);
    ceiling[i] = es.eigenvalues()(2) / model.mass[i];
    largest_trace = std::max(largest_trace, D[i].trace() / model.mass[i]);
  }
  for (size_t i = 0; i < n; ++i)
    if (!model.spec().fixed[i]) ceiling[i] += 1e-12 * largest_trace;
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

double semi_implicit_stability_index(const Model& model, const SparseMatrix& K_weighted,
                                     const std::vector<double>& gamma, double dt) {
  SparseMatrix S = (dt * dt) * K_weighted;
  std::vector<Eigen::Triplet<double>> diag;
  int b = 0;
  for (size_t i = 0; i < model.spec().rest.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    for (int r = 0; r < 3; ++r) diag.emplace_back(3 * b + r, 3 * b + r, 2.0 * dt * gamma[i] / model.mass[i]);
    ++b;
  }
  SparseMatrix D(S.rows(), S.cols());
  D.setFromTriplets(diag.begin(), diag.end());
  S += D;
  return largest_eigenvalue(S);
}

}  // namespace dampbound
