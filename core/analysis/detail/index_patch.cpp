// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/index_patch.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/analysis/detail/cholesky_rounding.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"

namespace dampbound::detail {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

double largest_abs_row_sum(const Eigen::MatrixXd& S) {
  return S.rows() ? S.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
}

/// The spring behind an entry of Model::incident, and the node at its other end.
struct Incident {
  size_t spring;
  size_t other;
};
Incident incident(const Model& model, int e) {
  const int k = model.incident[static_cast<size_t>(e)];
  const size_t spring = static_cast<size_t>(k >= 0 ? k : ~k);
  const Spring& s = model.spec().springs[spring];
  return {spring, static_cast<size_t>(k >= 0 ? s.j : s.i)};
}

}  // namespace

IndexPatch::IndexPatch(const Model& model, const std::vector<Vec3>& x, const SparseMatrix& A,
                       const Eigen::VectorXd& R, const std::vector<double>& ceiling, double gamma,
                       double h, double at_least, int layers)
    : A_(A) {
  int nfree = 0;
  const std::vector<int> block = free_blocks(model, &nfree);
  const size_t n = model.spec().rest.size();
  if (!(at_least > 0) || ceiling.size() != n || R.size() != 3 * nfree) return;
  // The seeds, then `layers` rings of neighbours through the springs.
  std::vector<char> in(n, 0);
  std::vector<int> ring;
  for (size_t i = 0; i < n; ++i)
    if (block[i] >= 0 && h * h * ceiling[i] + 2 * h * gamma * R(3 * block[i]) >= at_least) {
      in[i] = 1;
      ring.push_back(static_cast<int>(i));
    }
  size_t count = ring.size();
  if (count == 0 || count > kMaxNodes) return;
  for (int layer = 0; layer < layers; ++layer) {
    std::vector<int> next;
    for (const int i : ring)
      for (int e = model.incident_offset[i]; e < model.incident_offset[i + 1]; ++e) {
        const size_t j = incident(model, e).other;
        if (block[j] < 0 || in[j]) continue;
        in[j] = 1;
        next.push_back(static_cast<int>(j));
        if (++count > kMaxNodes) return;
      }
    ring = std::move(next);
  }
  std::vector<int> position(n, -1);
  for (size_t i = 0; i < n; ++i)
    if (in[i]) {
      position[i] = static_cast<int>(nodes_.size());
      nodes_.push_back(static_cast<int>(i));
      for (int r = 0; r < 3; ++r) dofs_.push_back(3 * block[i] + r);
    }
  const Eigen::Index p = static_cast<Eigen::Index>(dofs_.size());
  Eigen::Matrix3d B;
  // The edge: each free node j outside P with springs into it. Its block is D_j = (its other
  // springs, split as in splitting_ceilings, and its anchor) + c_j X_j, X_j the sum of its
  // springs into P, whose patch nodes then take (1 + a_j) of them, a_j = 1 / (c_j - 1). c_j
  // is the largest (up to 1e6) that keeps j's own bound on the index under 0.8 `at_least`
  // (it cannot then hold the top, and keeps room below it at the gammas and dts up to the
  // limits, where the bisections evaluate it), else 2 (a_j = 1, the plain splitting).
  std::vector<int> edge;
  std::vector<int> edge_position(n, -1);
  std::vector<Eigen::Matrix3d> across, rest_of;
  for (const int i : nodes_)
    for (int e = model.incident_offset[i]; e < model.incident_offset[i + 1]; ++e) {
      const Incident s = incident(model, e);
      const size_t j = s.other;
      if (block[j] < 0 || in[j] || !positive_spring_block(model, x, s.spring, B)) continue;
      if (edge_position[j] < 0) {
        edge_position[j] = static_cast<int>(edge.size());
        edge.push_back(static_cast<int>(j));
        across.push_back(Eigen::Matrix3d::Zero());
      }
      across[static_cast<size_t>(edge_position[j])] += B;
    }
  const double ceiling_room = 3e-12 * *std::max_element(ceiling.begin(), ceiling.end());
  std::vector<double> share(edge.size()), edge_ceiling(edge.size());
  for (size_t q = 0; q < edge.size(); ++q) {
    const size_t j = static_cast<size_t>(edge[q]);
    Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
    for (int e = model.incident_offset[j]; e < model.incident_offset[j + 1]; ++e) {
      const Incident s = incident(model, e);
      if (block[s.other] >= 0 && in[s.other]) continue;  // across: X_j
      if (!positive_spring_block(model, x, s.spring, B)) continue;
      D += block[s.other] < 0 ? B : Eigen::Matrix3d(2 * B);
    }
    D.diagonal().array() += model.anchor_kappa[j];
    const double m = model.mass[j], damping = 2 * h * gamma * R(3 * block[j]);
    const auto bound = [&](double c) {  // lambda_max(D + c X_j) / m_j
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(D + c * across[q],
                                                              Eigen::EigenvaluesOnly);
      return es.eigenvalues()(2) / m + ceiling_room;
    };
    const auto fits = [&](double c) { return h * h * bound(c) + damping <= 0.8 * at_least; };
    double c = 2;
    if (fits(1 + 1e-6)) {  // the largest c that fits, by bisection on log c
      double lo = std::log(1 + 1e-6), hi = std::log(1e6 + 1);
      if (fits(std::exp(hi))) lo = hi;
      for (int k = 0; k < 40 && hi - lo > 1e-3; ++k) {
        const double mid = (lo + hi) / 2;
        (fits(std::exp(mid)) ? lo : hi) = mid;
      }
      c = std::exp(lo);
    }
    share[q] = 1 / (c - 1);
    edge_ceiling[q] = bound(c);
  }
  // K_P+: the springs inside P whole, the edge's (1 + a_j) on its patch node, the anchors.
  upper_ = Eigen::MatrixXd::Zero(p, p);
  for (const int i : nodes_) {
    const Eigen::Index pi = 3 * position[static_cast<size_t>(i)];
    upper_.block<3, 3>(pi, pi).diagonal().array() += model.anchor_kappa[static_cast<size_t>(i)];
    for (int e = model.incident_offset[i]; e < model.incident_offset[i + 1]; ++e) {
      const Incident s = incident(model, e);
      const size_t j = s.other;
      if (block[j] >= 0 && in[j] && static_cast<size_t>(i) > j) continue;  // seen from j
      if (!positive_spring_block(model, x, s.spring, B)) continue;
      if (block[j] < 0) {  // to a fixed node: its part on i alone
        upper_.block<3, 3>(pi, pi) += B;
      } else if (in[j]) {
        const Eigen::Index pj = 3 * position[j];
        upper_.block<3, 3>(pi, pi) += B;
        upper_.block<3, 3>(pj, pj) += B;
        upper_.block<3, 3>(pi, pj) -= B;
        upper_.block<3, 3>(pj, pi) -= B;
      } else {
        upper_.block<3, 3>(pi, pi) += (1 + share[static_cast<size_t>(edge_position[j])]) * B;
      }
    }
  }
  for (Eigen::Index r = 0; r < p; ++r)
    for (Eigen::Index c = 0; c < p; ++c)
      upper_(r, c) /=
          std::sqrt(model.mass[static_cast<size_t>(nodes_[static_cast<size_t>(r / 3)])] *
                    model.mass[static_cast<size_t>(nodes_[static_cast<size_t>(c / 3)])]);
  entry_room_ = 1e-12 * largest_abs_row_sum(upper_);
  // Outside P: splitting_ceilings' bound, and on the edge the bound with its share.
  for (size_t i = 0; i < n; ++i) {
    if (block[i] < 0 || in[i]) continue;
    outside_ceiling_.push_back(
        edge_position[i] >= 0 ? edge_ceiling[static_cast<size_t>(edge_position[i])] : ceiling[i]);
    outside_rate_.push_back(R(3 * block[i]));
  }
  // A's principal submatrix on P, and R there.
  std::vector<int> local(static_cast<size_t>(A.rows()), -1);
  for (Eigen::Index q = 0; q < p; ++q)
    local[static_cast<size_t>(dofs_[static_cast<size_t>(q)])] = static_cast<int>(q);
  principal_ = Eigen::MatrixXd::Zero(p, p);
  rate_.resize(p);
  for (Eigen::Index q = 0; q < p; ++q) {
    const int col = dofs_[static_cast<size_t>(q)];
    rate_(q) = R(col);
    for (SparseMatrix::InnerIterator it(A, col); it; ++it) {
      const int r = local[static_cast<size_t>(it.row())];
      if (r >= 0) principal_(r, q) = it.value();
    }
  }
}

double IndexPatch::outside(double gamma, double h) const {
  double top = 0;
  for (size_t j = 0; j < outside_ceiling_.size(); ++j)
    top = std::max(top, h * h * outside_ceiling_[j] + 2 * h * gamma * outside_rate_[j]);
  return top * (1 + 1e-12);  // the rounding of the two products and the sum
}

Eigen::MatrixXd IndexPatch::index_matrix(const Eigen::MatrixXd& a, double gamma, double h) const {
  Eigen::MatrixXd S = (h * h) * a;
  S.diagonal() += (2 * h * gamma) * rate_;
  return S;
}

bool IndexPatch::proved_below(double t, double gamma, double h) const {
  if (!found() || !(outside(gamma, h) < t)) return false;
  const Eigen::MatrixXd S = index_matrix(upper_, gamma, h);
  const double rows = largest_abs_row_sum(S);
  // S's entries against the exact bound's: upper_'s own room, then one rounding each for the
  // scaling and the damping term.
  const double entries = h * h * entry_room_ + 4 * kEps * rows;
  // The shift lies `slack` under t - entries; a factor whose rounding bound exceeds the slack
  // (a factor that fills in, near singular) is tried once more with the slack widened to
  // twice that bound, and the widest slack needed so far starts the next call.
  double slack = std::max(1e-12 * (std::abs(t) + rows), slack_hint_);
  const Eigen::Index n = S.rows();
  for (int attempt = 0; attempt < 2; ++attempt) {
    Eigen::MatrixXd C = -S;
    C.diagonal().array() += t - entries - slack;
    const Eigen::LLT<Eigen::MatrixXd> llt(C);
    if (llt.info() != Eigen::Success) return false;
    // lambda_max(S) < shift + delta, the shift being t - entries - slack, with delta the
    // factor's rounding bound (detail/cholesky_rounding.hpp: Higham's Theorem 10.3, a dense
    // row of L holding up to n entries).
    const Eigen::MatrixXd L = llt.matrixL();
    const Eigen::VectorXd column_sums = L.cwiseAbs().colwise().sum().transpose();
    const double delta = rounding_bound((L.cwiseAbs() * column_sums).maxCoeff(), n,
                                        C.diagonal().cwiseAbs().maxCoeff());
    if (delta < slack) return true;
    slack = 2 * delta;
    slack_hint_ = std::max(slack_hint_, slack);
  }
  return false;
}

double IndexPatch::index_at_most(double gamma, double h) const {
  if (!found()) return std::numeric_limits<double>::infinity();
  const Eigen::MatrixXd S = index_matrix(upper_, gamma, h);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S, Eigen::EigenvaluesOnly);
  const double top = std::max(es.eigenvalues().maxCoeff(), outside(gamma, h));
  const double room = 1e-11 * (std::abs(top) + largest_abs_row_sum(S));
  for (double step = room; step < 1e6 * room; step *= 10)
    if (proved_below(top + step, gamma, h)) return top + step;
  return std::numeric_limits<double>::infinity();
}

Eigen::VectorXd IndexPatch::vector(double gamma, double h) const {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(A_.rows());
  if (!found()) return u;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(index_matrix(principal_, gamma, h));
  const Eigen::VectorXd y = es.eigenvectors().col(es.eigenvectors().cols() - 1);
  for (size_t q = 0; q < dofs_.size(); ++q) u(dofs_[q]) = y(static_cast<Eigen::Index>(q));
  return u;
}

double IndexPatch::rayleigh_below(const Eigen::VectorXd& u) const {
  // linear_stability_cholesky.cpp's rayleigh() over the patch's rows alone (u is zero
  // elsewhere, so no other row enters the quotient), with its rounding bound.
  long double uAu = 0, abs_uAu = 0, uu = 0;
  double abs_row_sum = 0;
  int row_nonzeros = 0;
  for (const int r : dofs_) {
    double Au = 0, sum = 0;
    int count = 0;
    for (SparseMatrix::InnerIterator it(A_, r); it; ++it) {
      Au += it.value() * u(it.row());
      sum += std::abs(it.value());
      ++count;
    }
    abs_row_sum = std::max(abs_row_sum, sum);
    row_nonzeros = std::max(row_nonzeros, count);
    const long double product = static_cast<long double>(u(r)) * Au;
    uAu += product;
    abs_uAu += std::abs(product);
    uu += static_cast<long double>(u(r)) * u(r);
  }
  if (uu == 0) return -std::numeric_limits<double>::infinity();
  const double q = static_cast<double>(uAu / uu);
  return q - rayleigh_rounding(uAu, abs_uAu, uu, static_cast<long double>(dofs_.size()) + 1,
                               row_nonzeros, abs_row_sum, q);
}

}  // namespace dampbound::detail
