#pragma once
// The batched kernel's per-node lane data (core/sweep/detail/kernel_body.cpp includes this, nothing
// else) and its mirror of the safe bound of SPEC 9 (core/physics/safe_bound.cpp, core/physics/bounds.cpp):
// the same operations in the same order, lane by lane, so each lane rounds as step() does.
#include <cstdint>
#include <vector>

#include "core/physics/detail/simd.hpp"
#include "core/physics/detail/spring_block.hpp"

namespace dampbound::sweep_lanes {
// Internal linkage, as in simd.hpp: each compiled variant of the kernel (generic,
// AVX2, AVX-512) keeps its own copy.
namespace {

using simd::vd;
using simd::vl;

/// One node's state in all lanes: position, velocity, internal force (x, y, z each).
struct NodeBlock {
  vd x[3], v[3], f[3];
};

/// Per-node, per-lane parameters when the scene's scales are not uniform.
struct NodeParams {
  vd mass, md, lo, gu;  // m_i, m_i/dt, gamma_lo_i, user gamma_i
};

struct SpringData {
  int i, j;
  double rest_length, kappa_scale;
};

/// safe_row_sums' accumulators of one node in all lanes: K_ii's upper triangle (6), then
/// the off-diagonal row sums of |A| (3). Only the `safe` policy needs them.
struct SafeBlock {
  vd a[9];
};

/// |b| along row r of a symmetric block, left to right (spring_block.hpp).
inline vd row_abs(const vd* b, int r) {
  return block_row_abs(b, r, [](vd v) { return simd::abs(v); });
}

/// std::max(a, b) lane by lane: (a < b) ? b : a.
inline vd lane_max(vd a, vd b) { return a < b ? b : a; }

/// safe_row_sums at the state at t (positions in `blocks`): K_ii and the off-diagonal |A|
/// row sums of every free node, springs in the kernel's order (each node keeps its springs'
/// list order, so every accumulator adds in step()'s order). `mass` is the uniform m_i
/// (Uniform) or unused (node_params[i].mass).
template <bool Uniform>
void safe_pass(const std::vector<SpringData>& springs, const std::vector<NodeBlock>& blocks,
               const std::vector<NodeParams>& node_params,
               const std::vector<unsigned char>& fixed, const std::vector<double>& anchor_scale,
               vd kappa, vd mass, std::vector<SafeBlock>& safe) {
  const vd zero = simd::splat(0.0);
  for (size_t i = 0; i < safe.size(); ++i) {
    vd* a = safe[i].a;
    for (int k = 0; k < 9; ++k) a[k] = zero;
    a[0] = a[3] = a[5] = kappa * anchor_scale[i];  // kappa_a,i I (model.cpp set_params)
  }
  vd w = zero;  // 1 / sqrt(m_i m_j)
  if constexpr (Uniform) w = 1.0 / simd::sqrt(mass * mass);
  for (const SpringData& s : springs) {
    const NodeBlock& bi = blocks[static_cast<size_t>(s.i)];
    const NodeBlock& bj = blocks[static_cast<size_t>(s.j)];
    const vd d0 = bj.x[0] - bi.x[0];
    const vd d1 = bj.x[1] - bi.x[1];
    const vd d2 = bj.x[2] - bi.x[2];
    const vd length = simd::sqrt((d0 * d0 + d1 * d1) + d2 * d2);
    const vl ok = length > 0;  // else no direction: skipped (SPEC 1)
    const vd d[3] = {d0 / length, d1 / length, d2 / length};
    const vd ratio = s.rest_length / length;
    const vd tension = 1.0 - ratio;
    const vd kap = kappa * s.kappa_scale;
    vd b[6];
    spring_tangent_block(kap, tension, ratio, d, b);
    if constexpr (!Uniform)
      w = 1.0 / simd::sqrt(node_params[static_cast<size_t>(s.i)].mass *
                           node_params[static_cast<size_t>(s.j)].mass);
    // The off-diagonal row sums |B| w are the same at both ends: computed once per spring.
    const vd off[3] = {row_abs(b, 0) * w, row_abs(b, 1) * w, row_abs(b, 2) * w};
    const int ends[2][2] = {{s.i, s.j}, {s.j, s.i}};
    for (const auto& e : ends) {
      if (fixed[static_cast<size_t>(e[0])]) continue;
      vd* a = safe[static_cast<size_t>(e[0])].a;
      for (int k = 0; k < 6; ++k) a[k] = ok ? a[k] + b[k] : a[k];
      if (!fixed[static_cast<size_t>(e[1])])
        for (int r = 0; r < 3; ++r) a[6 + r] = ok ? a[6 + r] + off[r] : a[6 + r];
    }
  }
}

/// The safe policy's damping of one free node: R_i = max row of |A|, gamma_safe_i =
/// 2 m_i/dt - m_i dt R_i / 2 (safe_gamma), then clamp(gamma, lo, gamma_safe), or
/// max(gamma_safe, 0) when lo > gamma_safe (effective_damping).
inline vd safe_damping(const SafeBlock& s, vd mass_i, vd dt, vd lo_i, vd gu_i) {
  const vd* a = s.a;
  const vd r0 = row_abs(a, 0) / mass_i + a[6];
  const vd r1 = row_abs(a, 1) / mass_i + a[7];
  const vd r2 = row_abs(a, 2) / mass_i + a[8];
  const vd R = lane_max(lane_max(r0, r1), r2);
  const vd gs = 2.0 * mass_i / dt - mass_i * dt * R / 2.0;
  const vd clamped_g = gu_i < lo_i ? lo_i : (gs < gu_i ? gs : gu_i);
  return lo_i > gs ? lane_max(gs, simd::splat(0.0)) : clamped_g;
}

}  // namespace
}  // namespace dampbound::sweep_lanes
