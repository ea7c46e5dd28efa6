// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/inverse_lanczos.hpp"

#include <Spectra/SymEigsSolver.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace dampbound::detail {
namespace {

/// (shift I - A)^-1 as an operator for Spectra.
struct InverseOp {
  using Scalar = double;
  ShiftedCholesky* factor;
  Eigen::Index rows() const { return factor->size(); }
  Eigen::Index cols() const { return factor->size(); }
  void perform_op(const double* in, double* out) const { factor->solve(in, out); }
};

/// Spectra's restarts before inverse iteration takes over. Where shift-and-invert Lanczos
/// converges it takes 1 restart (9 solves) on the shipped scenes, at rest and after 20
/// steps, and 13 at most; where it does not (a cluster at the end of the spectrum, e.g. the
/// anchors' lambda = 1 of a perturbed plane), more restarts only delay the same inverse
/// iteration, which then gives the same bits.
constexpr int kLanczosRestarts = 20;

}  // namespace

bool short_inverse_lanczos(ShiftedCholesky& f, const Eigen::VectorXd& start, Eigen::VectorXd& u,
                           double tol) {
  const Eigen::Index n = f.size();
  const int k = static_cast<int>(std::min<Eigen::Index>(kShortSteps, n));
  Eigen::MatrixXd V(n, k);
  V.col(0) = start / start.norm();
  Eigen::VectorXd w(n);
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(k, k);
  for (int j = 0; j < k; ++j) {
    f.solve(V.col(j).data(), w.data());
    const auto basis = V.leftCols(j + 1);
    Eigen::VectorXd h = basis.transpose() * w;
    w -= basis * h;
    const Eigen::VectorXd h2 = basis.transpose() * w;
    w -= basis * h2;
    T(j, j) = h(j) + h2(j);
    const double b = w.norm();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(T.topLeftCorner(j + 1, j + 1));
    const double theta = es.eigenvalues()(j);
    const Eigen::VectorXd y = es.eigenvectors().col(j);
    if (b * std::abs(y(j)) < tol * std::abs(theta) || !(b > 0)) {
      u = basis * y;
      return true;
    }
    if (j + 1 == k) break;
    T(j, j + 1) = T(j + 1, j) = b;
    V.col(j + 1) = w / b;
  }
  return false;
}

void inverse_lanczos(ShiftedCholesky& f, Eigen::VectorXd& u, double tol) {
  const Eigen::Index n = f.size();
  InverseOp op{&f};
  Spectra::SymEigsSolver<InverseOp> eigs(op, 1, std::min<Eigen::Index>(n, 8));
  if (u.size() == n)
    eigs.init(u.data());
  else
    eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, kLanczosRestarts, tol);
  if (eigs.info() == Spectra::CompInfo::Successful && eigs.eigenvectors().cols() > 0) {
    u = eigs.eigenvectors().col(0);
    return;
  }
  if (u.size() != n) u = Eigen::VectorXd::LinSpaced(n, 0.3, 1.7).array().sin();
  Eigen::VectorXd next(n);
  for (int k = 0; k < 100; ++k) {
    u /= u.norm();
    f.solve(u.data(), next.data());
    u.swap(next);
  }
  u /= u.norm();
}

}  // namespace dampbound::detail
