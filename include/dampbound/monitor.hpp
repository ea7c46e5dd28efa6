#pragma once
// The monitor: the paper's bounds over a simulator that is not dampbound. Its arrays
// (positions, velocities, internal forces, damping) are read in place through Eigen::Map
// views, never copied; the topology (masses, springs, anchors) is copied once, when the
// Monitor is made. The stable public API: installed as <dampbound/monitor.hpp>.
//
// Units are the paper's: cm, s, and any consistent mass unit. Every function works for the
// paper's step (semi-implicit Euler, SPEC 2): v += a dt, then x += v dt.
#include "dampbound/physics/export.hpp"
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/forces.hpp"
#include "dampbound/physics/model.hpp"
#include "dampbound/physics/params.hpp"

namespace dampbound DAMPBOUND_API {

/// N x 3 doubles read in place: row i is node i's (x, y, z); rows `stride` doubles apart
/// (3 when packed, e.g. an (N, 3) C-ordered NumPy array or a std::vector<std::array<double,3>>).
using NodeVectors = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>, 0,
                               Eigen::OuterStride<>>;
/// N doubles read in place, `stride` doubles apart.
using NodeScalars = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<>>;
/// N doubles written in place, `stride` doubles apart.
using NodeScalarsOut = Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<>>;
/// S x 2 node indices of the springs, rows `stride` ints apart.
using SpringPairs = Eigen::Map<const Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>, 0,
                               Eigen::OuterStride<>>;

/// Views from pointer, count and stride (in elements of the row or scalar).
inline NodeVectors node_vectors(const double* data, Eigen::Index n, Eigen::Index stride = 3) {
  return NodeVectors(data, n, 3, Eigen::OuterStride<>(stride));
}
inline NodeScalars node_scalars(const double* data, Eigen::Index n, Eigen::Index stride = 1) {
  return NodeScalars(data, n, Eigen::InnerStride<>(stride));
}
inline NodeScalarsOut node_scalars_out(double* data, Eigen::Index n, Eigen::Index stride = 1) {
  return NodeScalarsOut(data, n, Eigen::InnerStride<>(stride));
}
inline SpringPairs spring_pairs(const int* data, Eigen::Index s, Eigen::Index stride = 2) {
  return SpringPairs(data, s, 2, Eigen::OuterStride<>(stride));
}

/// The one rule for a state (docs/embedding.md, "Bad input"): a NaN or infinite value is never
/// judged. Throws std::invalid_argument naming the array and its first bad node ("v[3] is not
/// finite (node 3)"). Every Monitor call and the Python module apply it to what they read.
void require_finite(NodeVectors a, const char* what);
void require_finite(NodeScalars a, const char* what);

/// What the runtime check of one step found (paper sec. 5, SPEC 3-4), over the free nodes.
struct MonitorReport {
  int violating = 0;         ///< nodes whose effective gamma is outside [gamma_lo, gamma_hi]
  int unstabilisable = 0;    ///< nodes with gamma_lo > gamma_hi: no damping satisfies both
  int clamped = 0;           ///< nodes whose gamma the policy changed, within the bounds
  int first_violating = -1;  ///< the lowest such node index, -1 when none
  int first_unstabilisable = -1;
  int unguaranteed = 0;        ///< nodes with gamma_lo > gamma_safe (SPEC 9; only when checked with x)
  int compressed_springs = 0;  ///< springs with l < l0 at x: K may be indefinite, SPEC 9 promises nothing
  bool ok() const { return violating == 0 && unstabilisable == 0; }
};

/// The exact linear stability of the paper's step (SPEC 7) at positions x with the user's
/// per-node damping gamma_i, linearised at x (tangent stiffness; at rest only spring
/// directions and anchors contribute). lambda_max by Lanczos, never a dense decomposition.
struct MonitorLimits {
  double lambda_max = 0;  ///< largest eigenvalue of M^-1 K (1/s^2)
  bool stable = false;    ///< the step at dt with these gamma_i does not grow
  double scale_lo = 0;    ///< s * gamma_i is stable at dt for scale_lo <= s < scale_hi
  double scale_hi = 0;    ///< (may be inf)
  double dt_max = 0;      ///< the largest stable dt with these gamma_i (s; may be inf)
  double rate_max = 0;  ///< uniform damping rate limit: gamma_i/m_i < 2/dt - lambda_max dt/2 (1/s)
  double dt_max_undamped = 0;  ///< 2/sqrt(lambda_max) (s)
  /// K is indefinite at x (a certified eigenvalue below 0; compressed springs can do it):
  /// a mode grows whatever the damping and dt, so `stable` is false, scale_lo = scale_hi = 0
  /// and dt_max = rate_max = dt_max_undamped = 0 (ExactStability::indefinite).
  bool indefinite = false;
  /// Set when one sparse factorisation would have exceeded max_factor_flops: what it would
  /// have cost (every number above is then NaN).
  std::optional<std::string> not_computed;
  /// Then, what plain Lanczos proves without a factorisation (ExactStability::Unfactored;
  /// docs/criteria.md; NaN when computed): lambda_max is at least lambda_max_at_least, and the
  /// step is unstable for s * gamma_i with every s >= scale_unstable_from (at dt) and for
  /// every dt >= dt_unstable_from (with these gamma_i); inf: not proved for any. With no
  /// spring compressed at x (K >= 0), Gershgorin on the index matrix (SPEC 9's safe bound)
  /// proves the other side: stable for every s in [0, scale_stable_up_to] (at dt) and every
  /// dt <= dt_stable_up_to (with these gamma_i), and `stable` where the given point is; NaN
  /// when a spring is compressed or no s is proved.
  double lambda_max_at_least = std::numeric_limits<double>::quiet_NaN();
  double scale_unstable_from = std::numeric_limits<double>::quiet_NaN();
  double dt_unstable_from = std::numeric_limits<double>::quiet_NaN();
  double scale_stable_up_to = std::numeric_limits<double>::quiet_NaN();
  double dt_stable_up_to = std::numeric_limits<double>::quiet_NaN();
};

/// A user's mass-spring system, seen by dampbound: masses, springs and (optional) anchors.
///
/// Bad input, one rule for every call (docs/embedding.md, "Bad input"): an array of the wrong
/// size, a NaN or infinite value in a state (x, v, force, gamma, rest), a gamma_i < 0, a dt
/// that is not finite and > 0 or a factor that is not finite and >= 0 throws
/// std::invalid_argument naming the array and its first bad node ("v[3] is not
/// finite (node 3)", require_finite); nothing is judged and no output is complete.
class Monitor {
 public:
  /// masses m_i > 0 (mass unit); springs as node index pairs with stiffness kappa_ij > 0
  /// (mass unit/s^2) and rest length l0_ij >= 0 (cm). Throws std::invalid_argument naming
  /// the first bad entry (index out of range, i == j, m <= 0, kappa <= 0, l0 < 0, non-finite).
  Monitor(NodeScalars mass, SpringPairs springs, NodeScalars stiffness, NodeScalars rest_length);

  /// Zero-rest-length anchors to rest positions X_i (SPEC 1): force -kappa_a,i (x_i - X_i);
  /// kappa_a,i = 0 means no anchor. Updates kappa_i of eq. 5.
  void set_anchors(NodeScalars anchor_stiffness, NodeVectors rest);
  /// Marks nodes that never move (nonzero = fixed): they are not judged.
  void set_fixed(const std::uint8_t* fixed, Eigen::Index n);

  /// Threads for every call's loops over the nodes and springs (1 by default, 0 = one per
  /// hardware thread). The results are the same bits on any count: each node's springs are
  /// added in index order, as step() does on threads. Loops under 2 x 16 384 items stay on
  /// the calling thread. The threads are kept between calls; calls made from several threads
  /// at once take turns on them. A copy of the monitor gets threads of its own.
  void set_threads(int threads);
  int threads() const;

  int node_count() const { return model_.spec().node_count(); }
  /// The copy of the topology in core's terms (model.lower_bound is eq. 5 per node).
  const Model& model() const { return model_; }

  /// Paper eq. 5 per node: gamma_lo_i = 2 sqrt(m_i kappa_i), kappa_i = the largest stiffness of
  /// the springs and anchor at i (SPEC 3) (mass unit/s).
  void lower_bounds(NodeScalarsOut out) const;

  /// Paper eq. 6 per node from the state at t: gamma_hi_i = |v_i m_i/dt + F_i| / |v_i|, +inf
  /// when v_i = 0 (mass unit/s). `force` is the internal force F_i (springs and anchors only,
  /// no damping, no external force), as internal_forces() computes it.
  void upper_bounds(NodeVectors v, NodeVectors force, double dt, NodeScalarsOut out) const;

  /// The runtime check of one step (paper sec. 5): bounds from (v, F) at t, the effective
  /// damping of every free node under `policy` (SPEC 4; `factor` for upper), its status.
  /// The `safe` policy needs the positions: use the overload that takes x (this one throws).
  /// `gamma` is the user's gamma_i (mass unit/s). Optional outputs: `gamma_eff` (the damping
  /// to use this step, mass unit/s), `upper` (gamma_hi_i) and `status` (one per node).
  MonitorReport check(NodeVectors v, NodeVectors force, NodeScalars gamma, double dt,
                      DampingPolicy policy = DampingPolicy::fixed, double factor = 1.0,
                      NodeScalarsOut* gamma_eff = nullptr, NodeScalarsOut* upper = nullptr,
                      NodeStatus* status = nullptr) const;

  /// SPEC 9 per node at positions x: gamma_safe_i = 2 m_i/dt - m_i dt R_i / 2 (mass unit/s),
  /// R_i the Gershgorin row sum of M^-1/2 K M^-1/2 (tangent stiffness at x); +inf for fixed
  /// nodes. Where every gamma_i < gamma_safe_i the paper's step linearised at x cannot grow.
  /// Returns the number of compressed springs (with one, K may be indefinite: no guarantee).
  int safe_bounds(NodeVectors x, double dt, NodeScalarsOut out) const;

  /// check() with the positions x at t as well, which the `safe` policy (SPEC 9) needs:
  /// gamma_eff = gamma clamped into [gamma_lo_i, gamma_safe_i] (gamma_safe_i, at least 0, where
  /// that is empty); the report counts `unguaranteed` and `compressed_springs` under any policy.
  MonitorReport check(NodeVectors x, NodeVectors v, NodeVectors force, NodeScalars gamma,
                      double dt, DampingPolicy policy, double factor = 1.0,
                      NodeScalarsOut* gamma_eff = nullptr, NodeScalarsOut* upper = nullptr,
                      NodeStatus* status = nullptr) const;

  /// F_i of SPEC 1 at positions x into `force` (N x 3, packed; copies x once). Returns the
  /// number of springs of zero length, which contribute nothing.
  int internal_forces(
      NodeVectors x,
      Eigen::Ref<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> force) const;

  /// SPEC 7's exact limits at positions x (copied once), for damping gamma_i and step dt.
  /// `max_factor_flops` (> 0; infinite: no limit): the most one sparse factorisation may
  /// cost (ExactOptions::max_factor_flops); over it nothing is computed (`not_computed`).
  MonitorLimits exact_limits(NodeVectors x, NodeScalars gamma, double dt,
                             double max_factor_flops = std::numeric_limits<double>::infinity()) const;

 private:
  void check_size(Eigen::Index n, const char* what) const;
  MonitorReport check_with(const std::vector<double>* safe, NodeVectors v, NodeVectors force,
                           NodeScalars gamma, double dt, DampingPolicy policy, double factor,
                           NodeScalarsOut* gamma_eff, NodeScalarsOut* upper,
                           NodeStatus* status) const;
  void check_range(const std::vector<double>* safe, NodeVectors v, NodeVectors force,
                   NodeScalars gamma, double dt, DampingPolicy policy, double factor,
                   NodeScalarsOut* gamma_eff, NodeScalarsOut* upper, NodeStatus* status,
                   int begin, int end, MonitorReport& r) const;
  /// The caller's x as core reads it, copied into workers_.x on the monitor's threads; the
  /// caller holds workers_.mutex.
  const std::vector<Vec3>& positions(NodeVectors x) const;
  Model model_ = compile_model(ModelSpec{}, Params{});  ///< compiled with unit m, kappa, gamma
  /// The calls' threads and buffers, kept between calls and used under the lock; a copy
  /// takes the thread count and starts threads of its own.
  struct Workers {
    Workers() = default;
    Workers(const Workers& other) { pass.threads = other.pass.threads; }
    Workers& operator=(const Workers& other) {
      if (this != &other) pass.threads = other.pass.threads;
      return *this;
    }
    std::mutex mutex;
    SpringPass pass;
    std::vector<Vec3> x, force;   ///< the positions as core reads them, the forces
    std::vector<double> row_sum;  ///< SPEC 9's R_i
  };
  mutable Workers workers_;
};

}  // namespace dampbound
