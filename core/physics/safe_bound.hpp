#pragma once
// The per-node bound that guarantees stability (SPEC 9): local (one pass over a node's
// springs and anchor) and sufficient (Gershgorin's theorem on the semi-implicit step's exact
// definiteness criterion, Q = 4 I - 2 dt C - dt^2 A positive definite; docs/criteria.md).
#include <Eigen/SparseCore>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "core/physics/safe_bound_damped.hpp"
#include "dampbound/physics/forces.hpp"
#include "dampbound/physics/model.hpp"

namespace dampbound {

/// Gershgorin row sums of A = M^-1/2 K M^-1/2 (K the tangent stiffness at positions x, SPEC 7)
/// over the free nodes: R_i = max over node i's three rows r of sum_s |A_rs| (all columns, the
/// diagonal too; columns of fixed nodes drop out), 1/s^2. R_i = 0 for a fixed node.
/// Reads the model's m_i, anchor and spring stiffnesses and fixed flags; x in cm. A spring of
/// zero length has no direction and is skipped (SPEC 1). Each node's springs are added in
/// index order (what the batched kernel mirrors bit for bit), so any thread count gives the
/// same bits. O(springs + nodes); `pass` (optional) brings the threads and keeps 9 doubles per node
/// between calls (step() computes these and the forces in one pass:
/// core/physics/detail/spring_pass.hpp).
/// Returns the number of compressed springs (0 < l < l0): with one, K may be indefinite and
/// the bound guarantees nothing (SPEC 9).
int safe_row_sums(const Model& model, const std::vector<Vec3>& x, std::vector<double>& row_sum,
                  SpringPass* pass = nullptr);

/// SPEC 9: gamma_safe = 2 m/dt - m dt R / 2 (mass unit / s). May be <= 0: then no damping
/// guarantees stability at this dt.
inline double safe_gamma(double m, double dt, double row_sum) {
  return 2.0 * m / dt - m * dt * row_sum / 2.0;
}

/// The user's gamma below which node i holds (gamma_i = gamma * scale < gamma_safe_i):
/// gamma_safe_i / scale; a node with scale 0 is undamped whatever the gamma, so it limits no
/// gamma (+inf) unless gamma_safe_i <= 0, where no gamma makes it hold (gamma_safe_i itself).
inline double safe_user_gamma(double gamma_safe_i, double scale) {
  if (scale > 0) return gamma_safe_i / scale;
  return gamma_safe_i > 0 ? std::numeric_limits<double>::infinity() : gamma_safe_i;
}

/// SPEC 9: dt_safe = (sqrt(c^2 + 4 R) - c) / R with c = gamma/m (s); 2/c when R = 0
/// (+inf when also c = 0).
double safe_dt(double m, double gamma, double row_sum);

/// The safe bound of one model at one state, node by node: SPEC 9's rows, or SPEC 10's
/// generalised rows (DampedSafeRows) where the model has dashpot or Rayleigh damping. The one
/// place that chooses between them, for every report (bounds, suggest, files, the tuner).
class NodeSafeBounds {
 public:
  NodeSafeBounds(const Model& model, const std::vector<Vec3>& x);
  /// gamma_safe_i at step dt (mass unit / s; may be <= 0).
  double gamma_safe(int node, double dt) const;
  /// dt_safe_i at nodal damping gamma_i (s; +inf when no margin ever closes).
  double dt_safe(int node, double gamma) const;
  double row_sum(int node) const { return row_sum_[static_cast<size_t>(node)]; }  ///< SPEC 9's R_i
  int compressed_springs() const { return compressed_; }

 private:
  const Model& model_;
  std::vector<double> row_sum_;
  int compressed_ = 0;
  std::optional<DampedSafeRows> damped_;
};

/// The safe bound over a whole model at one state, for reports (`bounds`, `check`, the tuner).
struct SafeBoundSummary {
  int free_nodes = 0;
  /// The user's gamma below which every free node holds, gamma_i = gamma * gamma_scale_i <
  /// gamma_safe_i: min over free nodes of gamma_safe_i / gamma_scale_i (mass unit / s; a node
  /// with scale 0 limits no gamma unless gamma_safe_i <= 0). With every scale 1 it is the
  /// smallest gamma_safe_i.
  double gamma_safe = 0;
  bool gamma_scaled = false;  ///< some free node has gamma_scale_i != 1
  int gamma_node = -1;        ///< the node where it is reached
  double row_sum = 0;         ///< R of that node (1/s^2)
  double dt_safe = 0;         ///< min over free nodes of dt_safe_i at the user's gamma_i (s)
  int dt_node = -1;
  int gamma_over = 0;         ///< free nodes with gamma_i >= gamma_safe_i (not guaranteed)
  /// Free nodes with gamma_lo_i > gamma_safe_i: critical damping cannot be guaranteed at this
  /// dt. `infeasible_dt` is the dt_safe_i at gamma_lo_i that would make each feasible.
  std::vector<int> infeasible;
  std::vector<double> infeasible_dt;
  int compressed_springs = 0;  ///< springs with l < l0: K may be indefinite (no guarantee)
};

/// Evaluates SPEC 9 at positions x with the model's m_i, gamma_i, lower bounds and step dt;
/// SPEC 10's generalised rows (DampedSafeRows) where the model has dashpot or Rayleigh damping
/// (then `row_sum` is SPEC 9's R of the node, for reference).
SafeBoundSummary safe_bound_summary(const Model& model, const std::vector<Vec3>& x, double dt);

}  // namespace dampbound
