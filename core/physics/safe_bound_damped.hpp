#pragma once
// SPEC 10's generalised safe bound: Gershgorin's rows of the semi-implicit step's definiteness
// criterion with the whole damping (nodal gamma, dashpots, Rayleigh), node by node. SPEC 9's
// rows are its special case without damping matrix (safe_bound.hpp); NodeSafeBounds there
// chooses between the two for every report.
#include <Eigen/SparseCore>
#include <vector>

#include "dampbound/physics/model.hpp"
#include "dampbound/physics/node_threads.hpp"

namespace dampbound {

/// SPEC 10's generalised safe bound: Gershgorin's rows of Q = 4 I - 2 dt C^ - dt^2 A with C^ =
/// M^-1/2 (Gamma + C') M^-1/2 (C' = alpha M + beta K + dashpots, damping_matrix.hpp). Row r of
/// free node i has the margin
///   4 - 2 dt C^_rr - dt^2 A_rr - sum_{s != r} |2 dt C^_rs + dt^2 A_rs|,
/// the diagonal signed, every other entry of the row (node i's own block and each free
/// neighbour's, spring by spring) in absolute value. Built once per state; gamma_safe and
/// dt_safe then cost a pass over the node's rows. With kd = alpha = beta = 0 the margins are
/// SPEC 9's up to |A_rr| (equal unless a compressed spring makes A_rr negative); step() and
/// the reports use SPEC 9's own formulas there, so those numbers keep their bits.
class DampedSafeRows {
 public:
  DampedSafeRows(const Model& model, const std::vector<Vec3>& x);
  /// The same rows from a user's matrices (linear_limits): A = M^-1/2 K M^-1/2 and
  /// Cp = M^-1/2 C M^-1/2 (3N square, symmetric), node i's rows 3i..3i+2, masses m_i (N;
  /// kept by reference: they must outlive the rows). Every node is free.
  DampedSafeRows(const Eigen::SparseMatrix<double>& A, const Eigen::SparseMatrix<double>& Cp,
                 const std::vector<double>& mass);
  /// The largest nodal gamma_i keeping every margin of node i positive at dt, the other
  /// damping held: m_i / (2 dt) * min_r (margin_r without the nodal term). May be <= 0.
  double gamma_safe(int node, double dt) const;
  /// The largest dt with every margin of node i positive on (0, dt] at nodal damping gamma
  /// (the first root of the piecewise quadratic margins); +inf when none ever closes.
  double dt_safe(int node, double gamma) const;

 private:
  struct Entry {
    double a, c;  ///< A_rs and C'^_rs (both weighted by 1/sqrt(m_r m_s))
  };
  const std::vector<double>& mass_;      ///< m_i
  std::vector<double> diag_a_, diag_c_;  ///< per node 3 rows: A_rr and C'^_rr (alpha included)
  std::vector<int> offset_;              ///< row (3 i + r)'s entries: [offset_[3i+r], offset_[3i+r+1])
  std::vector<Entry> entries_;
};

/// DampedSafeRows(model, x).gamma_safe(i, dt) for every node (+inf at fixed nodes), the same
/// bits, in one pass that stores no row: what step() calls each step, on its node threads
/// (`threads`, optional: the same bits on any count).
void damped_safe_gammas(const Model& model, const std::vector<Vec3>& x, double dt,
                        std::vector<double>& gamma_safe, NodeThreads* threads = nullptr);

}  // namespace dampbound
