#pragma once
// The trial body's terms besides the springs and the nodes (core/sweep/detail/trial_body.hpp),
// for the host and the GPU alike: SPEC 10's damping force D' (forces.cpp damping_forces), its
// generalised safe bound (safe_bound_damped.cpp damped_safe_gammas) and SPEC 9's row sums of
// the safe policy (detail/spring_pass.cpp, as the batched kernel's sweep_lanes::safe_pass
// mirrors them), each with step()'s operands in step()'s order. Arrays of the trial's state
// hold element k at [k * w].
#include <cmath>
#include <cstddef>

#include "core/physics/detail/spring_block.hpp"
#include "core/sweep/detail/trial_data.hpp"
#include "dampbound/physics/host_device.hpp"

namespace dampbound::trial_body {

struct Fabs {
  DAMPBOUND_HD double operator()(double v) const { return fabs(v); }
};

/// SPEC 10: D'_i = (alpha m_i + kd_a,i + beta kappa_a,i) v_i - sum over springs (i, j) of
/// [kd_ij ((v_j - v_i) . d) d + beta B_ij (v_j - v_i)], the opposite on j; fixed nodes count as
/// still and get 0; a spring of zero length adds nothing.
DAMPBOUND_HD inline void damping_forces(const FlatModel& M, const TrialConsts& P, const double* x,
                                        const double* v, double* D, std::size_t w) {
  for (int i = 0; i < M.nodes; ++i) {
    const double mass = P.m * M.mass_scale[i];
    const double anchor_kd = M.anchor_scale[i] > 0 ? P.kd * M.anchor_kd_scale[i] : 0.0;
    const double coef = P.alpha * mass + anchor_kd + P.beta * (P.kappa * M.anchor_scale[i]);
    for (int c = 0; c < 3; ++c) D[(3 * i + c) * w] = M.fixed[i] ? 0.0 : coef * v[(3 * i + c) * w];
  }
  for (int k = 0; k < M.springs; ++k) {
    const int i = M.spring_i[k], j = M.spring_j[k];
    double delta[3];
    for (int c = 0; c < 3; ++c) delta[c] = x[(3 * j + c) * w] - x[(3 * i + c) * w];
    const double l = sqrt((delta[0] * delta[0] + delta[1] * delta[1]) + delta[2] * delta[2]);
    if (!(l > 0)) continue;  // no direction (also NaN): no force, as for the spring (SPEC 1)
    double d[3], u[3];
    for (int c = 0; c < 3; ++c) {
      d[c] = delta[c] / l;
      const double vi = M.fixed[i] ? 0.0 : v[(3 * i + c) * w];
      const double vj = M.fixed[j] ? 0.0 : v[(3 * j + c) * w];
      u[c] = vj - vi;
    }
    const double kappa = P.kappa * M.kappa_scale[k];
    const double kd = P.kd * M.kd_scale[k];
    const double ratio = M.rest_length[k] / l, tension = 1.0 - ratio;
    const double along = (u[0] * d[0] + u[1] * d[1]) + u[2] * d[2];
    for (int c = 0; c < 3; ++c) {
      const double wc =
          (kd * along) * d[c] + P.beta * (kappa * (tension * u[c] + (ratio * along) * d[c]));
      if (!M.fixed[i]) D[(3 * i + c) * w] = D[(3 * i + c) * w] - wc;
      if (!M.fixed[j]) D[(3 * j + c) * w] = D[(3 * j + c) * w] + wc;
    }
  }
}

/// Spring k's blocks at x (safe_bound_damped.cpp): K's B = kappa (ratio P + tension I) and
/// C''s E = beta B + kd P, P = d d^T, row-major 3 x 3; false when it has no direction.
DAMPBOUND_HD inline bool spring_blocks(const FlatModel& M, const TrialConsts& P, const double* x,
                                       std::size_t w, int k, double B[9], double E[9]) {
  const int i = M.spring_i[k], j = M.spring_j[k];
  double delta[3];
  for (int c = 0; c < 3; ++c) delta[c] = x[(3 * j + c) * w] - x[(3 * i + c) * w];
  const double l = sqrt((delta[0] * delta[0] + delta[1] * delta[1]) + delta[2] * delta[2]);
  if (!(l > 0)) return false;
  const double d[3] = {delta[0] / l, delta[1] / l, delta[2] / l};
  const double ratio = M.rest_length[k] / l, tension = 1.0 - ratio;
  const double kappa = P.kappa * M.kappa_scale[k], kd = P.kd * M.kd_scale[k];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const double p = d[r] * d[c];
      B[3 * r + c] = kappa * (ratio * p + tension * (r == c ? 1.0 : 0.0));
      E[3 * r + c] = P.beta * B[3 * r + c] + kd * p;
    }
  return true;
}

/// SPEC 10's gamma_safe_i of every free node at x (damped_safe_gammas): from the rows of
/// A = M^-1 K and C' = alpha + M^-1 (beta K + dashpots), gamma_safe_i = m_i/(2 dt) min over
/// the node's rows of (4 - 2 dt C'_rr - dt^2 A_rr - sum_(c != r) |2 dt C'_rc + dt^2 A_rc|).
/// Node i's value goes to out[(per * i) * w].
DAMPBOUND_HD inline void damped_safe_gammas(const FlatModel& M, const TrialConsts& P,
                                            const double* x, double* out, int per, std::size_t w) {
  constexpr double inf = __builtin_huge_val();
  const double dt = P.dt;
  for (int i = 0; i < M.nodes; ++i) {
    out[(per * i) * w] = inf;
    if (M.fixed[i]) continue;
    const double m = P.m * M.mass_scale[i];
    const double ka = P.kappa * M.anchor_scale[i];
    const double anchor_kd = M.anchor_scale[i] > 0 ? P.kd * M.anchor_kd_scale[i] : 0.0;
    const double kc = P.beta * ka + anchor_kd;
    double Ka[9], Kc[9], B[9], E[9];
    for (int e = 0; e < 9; ++e) {
      const double id = e % 4 == 0 ? 1.0 : 0.0;  // the identity's entry (0, 4, 8: diagonal)
      Ka[e] = ka * id;
      Kc[e] = kc * id;
    }
    double off[3] = {0, 0, 0};  // neighbours' entries first, then the node's own block
    for (int e = M.incident_offset[i]; e < M.incident_offset[i + 1]; ++e) {
      const int code = M.incident[e];
      const int k = code >= 0 ? code : ~code;
      if (!spring_blocks(M, P, x, w, k, B, E)) continue;
      for (int q = 0; q < 9; ++q) {
        Ka[q] = Ka[q] + B[q];
        Kc[q] = Kc[q] + E[q];
      }
      const int j = code >= 0 ? M.spring_j[k] : M.spring_i[k];
      if (M.fixed[j]) continue;
      const double wt = 1.0 / sqrt(m * (P.m * M.mass_scale[j]));
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          off[r] += fabs(2 * dt * (-E[3 * r + c] * wt) + dt * dt * (-B[3 * r + c] * wt));
    }
    double margin = inf;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c)
        if (c != r) off[r] += fabs(2 * dt * (Kc[3 * r + c] / m) + dt * dt * (Ka[3 * r + c] / m));
      const double diag_c = P.alpha + Kc[4 * r] / m, diag_a = Ka[4 * r] / m;
      const double value = 4 - 2 * dt * diag_c - dt * dt * diag_a - off[r];
      margin = value < margin ? value : margin;  // std::min(margin, value)
    }
    out[(per * i) * w] = m / (2 * dt) * margin;
  }
}

/// SPEC 9's accumulators of every node at x (the batched kernel's safe_pass): K_ii's upper
/// triangle (6) and the off-diagonal row sums of |A| (3), springs in list order, so each
/// accumulator adds in step()'s order. Node i's at acc[(per * i + q) * w], q < 9.
DAMPBOUND_HD inline void safe_row_sums(const FlatModel& M, const TrialConsts& P, const double* x,
                                       double* acc, int per, std::size_t w) {
  for (int i = 0; i < M.nodes; ++i) {
    for (int q = 0; q < 9; ++q) acc[(per * i + q) * w] = 0;
    const double ka = P.kappa * M.anchor_scale[i];  // kappa_a,i I (model.cpp set_params)
    acc[(per * i) * w] = acc[(per * i + 3) * w] = acc[(per * i + 5) * w] = ka;
  }
  for (int k = 0; k < M.springs; ++k) {
    const int i = M.spring_i[k], j = M.spring_j[k];
    const double d0 = x[(3 * j) * w] - x[(3 * i) * w];
    const double d1 = x[(3 * j + 1) * w] - x[(3 * i + 1) * w];
    const double d2 = x[(3 * j + 2) * w] - x[(3 * i + 2) * w];
    const double length = sqrt((d0 * d0 + d1 * d1) + d2 * d2);
    if (!(length > 0)) continue;  // no direction: skipped (SPEC 1)
    const double d[3] = {d0 / length, d1 / length, d2 / length};
    const double ratio = M.rest_length[k] / length;
    const double tension = 1.0 - ratio;
    const double kap = P.kappa * M.kappa_scale[k];
    double b[6];
    spring_tangent_block(kap, tension, ratio, d, b);
    const double wt = 1.0 / sqrt((P.m * M.mass_scale[i]) * (P.m * M.mass_scale[j]));
    // The off-diagonal row sums |B| w are the same at both ends: computed once per spring.
    const double off[3] = {block_row_abs(b, 0, Fabs()) * wt, block_row_abs(b, 1, Fabs()) * wt,
                           block_row_abs(b, 2, Fabs()) * wt};
    const int ends[2][2] = {{i, j}, {j, i}};
    for (const auto& e : ends) {
      if (M.fixed[e[0]]) continue;
      double* a = acc + (per * e[0]) * w;
      for (int q = 0; q < 6; ++q) a[q * w] = a[q * w] + b[q];
      if (!M.fixed[e[1]])
        for (int r = 0; r < 3; ++r) a[(6 + r) * w] = a[(6 + r) * w] + off[r];
    }
  }
}

/// SPEC 9's gamma_safe_i from node i's accumulators `a` (safe_row_sums): R_i = the largest
/// row of |A|, gamma_safe_i = 2 m_i/dt - m_i dt R_i / 2 (safe_gamma).
DAMPBOUND_HD inline double safe_gamma_nodal(const double* a, std::size_t w, double mass,
                                            double dt) {
  double k[6];
  for (int q = 0; q < 6; ++q) k[q] = a[q * w];
  const double r0 = block_row_abs(k, 0, Fabs()) / mass + a[6 * w];
  const double r1 = block_row_abs(k, 1, Fabs()) / mass + a[7 * w];
  const double r2 = block_row_abs(k, 2, Fabs()) / mass + a[8 * w];
  const double r01 = r0 < r1 ? r1 : r0;
  const double R = r01 < r2 ? r2 : r01;
  return 2.0 * mass / dt - mass * dt * R / 2.0;
}

}  // namespace dampbound::trial_body
