#pragma once
// The tangent stiffness block of one spring (SPEC 7), written once for every caller: the
// sparse K of the exact analysis (linear_stability.cpp), the per-node safe bound of SPEC 9
// (detail/spring_pass.cpp) and its lane-wise mirror in the batched kernel (sweep_kernel.cpp), which
// instantiates it with a SIMD lane vector so that both round the same way. The GPU sweep's
// trial body (sweep/detail/trial_body.hpp) calls it with doubles in device code too.
#include "core/host_device.hpp"

namespace dampbound {

/// B = kappa [ (1 - l0/l) I + (l0/l) d d^T ] = kappa [ d d^T + (1 - l0/l)(I - d d^T) ]
/// (mass unit / s^2) for a spring of stiffness `kappa`, unit direction `d`, with
/// `ratio` = l0/l and `tension` = 1 - l0/l. B is symmetric; `b` receives its upper
/// triangle {xx, xy, xz, yy, yz, zz}. T is double or a lane vector of doubles. Internal
/// linkage: each compiled variant of the batched kernel instantiates its own.
template <class T>
DAMPBOUND_HD static inline void spring_tangent_block(const T& kappa, const T& tension, const T& ratio, const T d[3],
                                 T b[6]) {
  const T r0 = ratio * d[0], r1 = ratio * d[1], r2 = ratio * d[2];
  b[0] = kappa * (tension + r0 * d[0]);
  b[1] = kappa * (r0 * d[1]);
  b[2] = kappa * (r0 * d[2]);
  b[3] = kappa * (tension + r1 * d[1]);
  b[4] = kappa * (r1 * d[2]);
  b[5] = kappa * (tension + r2 * d[2]);
}

/// Index into the upper triangle {xx, xy, xz, yy, yz, zz} of row r, column c of a symmetric 3x3.
DAMPBOUND_HD static constexpr int sym3(int r, int c) {
  return r <= c ? (r == 0 ? c : r == 1 ? 2 + c : 5) : sym3(c, r);
}

/// |.| of row r of a symmetric block (upper triangle `b`) summed left to right, the order
/// every caller keeps: `abs` is std::abs for doubles, simd::abs for lane vectors.
template <class T, class Abs>
DAMPBOUND_HD static inline T block_row_abs(const T* b, int r, Abs abs) {
  return (abs(b[sym3(r, 0)]) + abs(b[sym3(r, 1)])) + abs(b[sym3(r, 2)]);
}

}  // namespace dampbound
