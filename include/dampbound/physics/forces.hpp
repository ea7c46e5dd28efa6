#pragma once
// The internal force F_i of paper eq. 6 (SPEC 1): spring and anchor forces only, no damping,
// no external force.
#include "dampbound/physics/export.hpp"
#include <cstdint>
#include <vector>

#include "dampbound/physics/model.hpp"
#include "dampbound/physics/node_threads.hpp"
#include "dampbound/physics/step_isa.hpp"

namespace dampbound DAMPBOUND_API {

/// Threads and buffers of the spring loop (forces here, SPEC 9's row sums in safe_bound.hpp,
/// both at once in step(): core/physics/detail/spring_pass.hpp). Each thread owns a contiguous range
/// of nodes and adds the springs at its nodes in index order, so every node's sum is added in
/// the order of a serial loop over the springs and the result has the same bits on any number
/// of threads. step() keeps one in its workspace.
struct SpringPass {
  NodeThreads threads;
  std::vector<double> rows;          ///< per-node row-sum accumulators (9 doubles each)
  std::vector<int> counts;           ///< per-chunk counts (zero-length, compressed springs)
  /// Which compiled copy of the springs' arithmetic runs (include/dampbound/physics/step_isa.hpp); every copy gives
  /// the same bits.
  StepIsa isa = StepIsa::best;
};

/// F_i = sum_j kappa_ij (l_ij - l0_ij) d_ij  -  kappa_a,i (x_i - X_i),  d_ij = (x_j - x_i)/l_ij
/// (paper eq. 1, SPEC 1), each node's springs added in spring order after its anchor term.
/// `force` is resized to the node count. A spring of zero current length has no direction and
/// contributes nothing; the return value counts such springs. `pass` (optional) brings
/// threads and keeps the buffers between calls.
int internal_forces(const Model& model, const std::vector<Vec3>& x, std::vector<Vec3>& force,
                    SpringPass* pass = nullptr);

/// SPEC 10's damping forces besides the nodal -gamma_i v_i, as the force D'_i subtracted from
/// F_i (a_i = (F_i - gamma_i v_i - D'_i + f_i) / m_i), at positions x and velocities v:
///   D'_i = (alpha m_i + kd_a,i + beta kappa_a,i) v_i
///          - sum over springs (i, j) of [kd_ij ((v_j - v_i) . d) d + beta B_ij (v_j - v_i)],
/// B_ij the spring's tangent block (SPEC 7; l0/l and 1 - l0/l as they are, compressed too),
/// d = (x_j - x_i) / l, and the opposite on j: dashpots along springs and anchors plus
/// Rayleigh damping alpha M v + beta K(x) v, spring by spring (no matrix). Fixed nodes count
/// as still (v = 0) and get 0. A spring of zero length adds nothing (SPEC 1). `damping` is
/// resized to the node count; each node's terms are added in spring order after its anchor.
void damping_forces(const Model& model, const std::vector<Vec3>& x, const std::vector<Vec3>& v,
                    std::vector<Vec3>& damping);

}  // namespace dampbound
