#pragma once
// One spring's geometry (SPEC 1) and its tangent stiffness block (SPEC 7), each written once
// for every caller.
//
// spring_vector and spring_direction (spring_geometry for both in doubles): e = x_j - x_i,
// l = |e|, d = e / l, l0 / l and 1 - l0 / l. The step's forces
// and safe rows (detail/spring_batch.cpp), the tangent stiffness and damping matrices
// (stiffness.cpp), the viscous forces (forces.cpp), the damped safe rows (safe_bound_damped.cpp),
// the exact analysis (analysis/linear_stability.cpp), the equilibrium's energy and both sweep
// kernels (sweep/detail/kernel_body.cpp, trial_body.hpp) take it from here, with doubles or
// lane vectors, so that every one rounds as the step does.
//
// spring_tangent_block: written once for every caller: the
// sparse K of the exact analysis (linear_stability.cpp), the per-node safe bound of SPEC 9
// (detail/spring_pass.cpp) and its lane-wise mirror in the batched kernel (sweep/detail/kernel_body.cpp), which
// instantiates it with a SIMD lane vector so that both round the same way. The GPU sweep's
// trial body (sweep/detail/trial_body.hpp) calls it with doubles in device code too.
#include <cmath>

#include "dampbound/physics/host_device.hpp"

namespace dampbound {

namespace {  // internal linkage: the instruction-set copies of the kernels each keep their own
/// sqrt of a double, on the host and in device code.
struct ScalarSqrt {
  DAMPBOUND_HD double operator()(double a) const { return sqrt(a); }
};
}  // namespace

/// A spring's vector e = x_j - x_i and its length l = |e| = sqrt((e0^2 + e1^2) + e2^2), the
/// order Eigen's Vec3::norm() sums in. T is double or a lane vector of doubles; `root` its
/// square root (ScalarSqrt, or simd::Sqrt for lane vectors). Returns l.
template <class T, class Root = ScalarSqrt>
DAMPBOUND_HD static inline T spring_vector(const T xi[3], const T xj[3], T e[3], Root root = {}) {
  for (int c = 0; c < 3; ++c) e[c] = xj[c] - xi[c];
  return root((e[0] * e[0] + e[1] * e[1]) + e[2] * e[2]);
}

/// From e and l: the unit direction d = e / l, ratio = l0 / l and tension = 1 - l0 / l (< 0
/// when compressed). Callers test l > 0 first (SPEC 1: no direction, no force).
template <class T>
DAMPBOUND_HD static inline void spring_direction(const T e[3], const T& length, const T& rest,
                                                 T d[3], T& ratio, T& tension) {
  for (int c = 0; c < 3; ++c) d[c] = e[c] / length;
  ratio = rest / length;
  tension = 1.0 - ratio;
}

/// Both for one spring in doubles: what the host's per-spring loops read.
struct SpringGeometry {
  double e[3], length, d[3], ratio, tension;
};
DAMPBOUND_HD static inline SpringGeometry spring_geometry(const double xi[3], const double xj[3],
                                                          double rest) {
  SpringGeometry g;
  g.length = spring_vector(xi, xj, g.e);
  spring_direction(g.e, g.length, rest, g.d, g.ratio, g.tension);
  return g;
}

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
