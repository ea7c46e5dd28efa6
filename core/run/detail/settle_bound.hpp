#pragma once
// SPEC 8's early stop under the settled rule: a certificate that no later iteration can leave
// the restore band. The derivation is in docs/settled.md ("The proof"); the names below are
// its names. Plain arithmetic and DAMPBOUND_HD only: Session (core/run/session.cpp), the batched
// kernel (core/sweep/detail/kernel_body.cpp) and the host/GPU trial body
// (core/sweep/detail/trial_body.hpp) all call these functions on the same bits of the same
// state, so all three stop at the same iteration.
//
// In short: with uniform masses and nodal damping, the paper's step linearised at rest is, mode
// by mode, (u, w) -> T (u, w) with w = dt v, a = dt^2 lambda, b = dt gamma / m, and the form
//   Q(a) = [[a, -(a - b) / 2], [-(a - b) / 2, 1 - b]]
// satisfies T^T Q T = (1 - b) Q exactly. Summed over the modes that is
//   N^2 = (u - w)^T A^ u + b u.w + (1 - b) w.w,   A^ = dt^2 M^-1 K (K at rest),
// a norm where every mode is under-damped (h(a) = 4 a (1 - b) - (a - b)^2 > 0 on the
// spectrum). The ball N <= nu is invariant under the real (nonlinear, rounded) step when
// sqrt(1 - b) nu + (springs' nonlinear remainder) + (rounding) <= nu, and inside it
// max_i |u_i| <= |u| <= nu / sqrt(sigma) < the restore threshold.
#include <cmath>

#include "core/physics/detail/spring_block.hpp"
#include "dampbound/physics/host_device.hpp"
#include "dampbound/run/verdict.hpp"

namespace dampbound::settle {

/// The unit roundoff of a double, 2^-53.
constexpr double kUnit = 1.1102230246251565e-16;

/// The scene's part of the certificate, computed once on the host (core/run/settle_proof.cpp)
/// and copied as plain data (the GPU sweep copies it inside FlatModel).
struct SceneBound {
  bool eligible = false;  ///< uniform masses and gammas, anchored free nodes, fixed policy, ...
  double mass_scale = 1, gamma_scale = 1;  ///< every free node's (uniform) scales
  double mu_lo = 0, mu_hi = 0;  ///< the spectrum of the stiffness scales' matrix G lies in
                                ///< [mu_lo, mu_hi] (K = kappa G at rest)
  double degree = 0;            ///< most springs at a free node
  /// The springs' remainder summed over the mesh: |R|_2 <= kappa k_max c(rho) spread U^2 /
  /// l0_min (docs/settled.md, step 4).
  double spread = 0;
  double k_max = 0, anchor_max = 0;  ///< largest spring and anchor stiffness scales
  double l0_min = 0, l0_max = 0;     ///< rest lengths of springs with a free end
  double x_max = 0;                  ///< largest |X_i,c|
  double coords = 0;                 ///< 3 x free nodes
  double nodes = 0, springs = 0;     ///< counts, for the rounding of the norm's sums
};

/// What the norm reads: the scene's arrays (spring list order), anywhere they live.
struct SceneArrays {
  int nodes = 0, springs = 0;
  const int* spring_i = nullptr;
  const int* spring_j = nullptr;
  const double* kappa_scale = nullptr;
  const double* rest = nullptr;  // 3 per node
  const double* anchor_scale = nullptr;
  const unsigned char* fixed = nullptr;
  /// Each spring's unit direction at rest, 3 per spring, as norm_bound computes it from
  /// `rest` (e / l, spring_vector); null: computed on the fly (the GPU's trial body).
  const double* direction = nullptr;
};

/// Spring k's unit direction at rest, d = e / l with spring_vector's e and l.
DAMPBOUND_HD inline void rest_direction(const SceneArrays& g, int k, double d[3]) {
  if (g.direction) {
    for (int c = 0; c < 3; ++c) d[c] = g.direction[3 * k + c];
    return;
  }
  double e[3];
  const double l = spring_vector(g.rest + 3 * g.spring_i[k], g.rest + 3 * g.spring_j[k], e);
  for (int c = 0; c < 3; ++c) d[c] = e[c] / l;
}

/// A trial's part: kappa, s = dt^2 / m_i, b = dt gamma_i / m_i, dt and the invariant radius
/// squared nu^2 (0: no certificate for this trial; its settled runs go to the limit).
struct TrialBound {
  double kappa = 0, s = 0, b = 0, dt = 0, nu_sq = 0;
  /// nu^2 / sigma: a state whose largest displacement squared exceeds this is outside the
  /// ball (N^2 >= sigma |u|^2), so the norm is not computed there.
  double u_max_sq = 0;
};

DAMPBOUND_HD inline double min2(double a, double b) { return a < b ? a : b; }

/// h(a) = 4 a (1 - b) - (a - b)^2 less a bound on its rounding: > 0 means a mode of that a is
/// under-damped (complex roots of the step's characteristic polynomial, SPEC 7).
DAMPBOUND_HD inline double h_low(double a, double b) {
  const double h = 4.0 * a * (1.0 - b) - (a - b) * (a - b);
  return h - 16.0 * kUnit * (4.0 * a + (a + b) * (a + b));
}

/// The trial's certificate (docs/settled.md, "The proof", steps 1-5). `threshold` is the
/// restore threshold (fraction x reference, cm); `widen` multiplies the radius (1; the tests
/// widen it to show that a weakened certificate changes verdicts).
DAMPBOUND_HD inline TrialBound trial_bound(const SceneBound& g, double m, double kappa,
                                           double gamma, double dt, double threshold,
                                           double widen = 1.0) {
  TrialBound t;
  if (!g.eligible) return t;
  const double mass = m * g.mass_scale;  // compile_model()'s m_i
  const double gu = gamma * g.gamma_scale;
  t.kappa = kappa;
  t.dt = dt;
  t.s = (dt * dt) / mass;
  t.b = (dt * gu) / mass;
  const double b = t.b;
  if (!(b > 1e-9 && b < 1.0) || !(kappa > 0) || !(threshold > 0)) return t;
  // Step 1: the spectrum of A^ in [a_lo, a_hi], every mode under-damped there (h is concave
  // in a, so positive at both ends means positive between).
  const double a0 = kappa * t.s;
  const double a_lo = a0 * g.mu_lo * (1.0 - 1e-12);
  const double a_hi = a0 * g.mu_hi * (1.0 + 1e-12);
  const double h_min = min2(h_low(a_lo, b), h_low(a_hi, b));
  if (!(h_min > 0)) return t;
  // Relative slack for rounding the form's own coefficients (b, s, d, kappa_ij): the
  // condition number of Q over the spectrum must leave it small.
  const double cond = 4.0 * (a_hi + 1.0) * (a_hi + 1.0) / h_min;
  if (!(cond < 1e6)) return t;
  // Step 2: |u|^2 <= N^2 / sigma, |w|^2 <= N^2 * 4 a_hi / h_min, N(d) <= q |d|.
  const double sigma = h_min / (4.0 * (1.0 - b)) * (1.0 - 1e-9);
  const double wide = sqrt(4.0 * a_hi / h_min) * (1.0 + 1e-9);
  const double q = sqrt(2.0 * (a_hi + 1.0)) * (1.0 + 1e-9);
  const double contraction = b / (1.0 + sqrt(1.0 - b)) * (1.0 - 1e-9);  // 1 - sqrt(1 - b)
  const double root_sigma = sqrt(sigma) * (1.0 - 1e-12);
  // Step 3: inside the ball |u_i| < threshold, with room for the displacement's rounding.
  double nu = threshold * (1.0 - 1e-6) * root_sigma;
  const double kk = kappa * g.k_max * (1.0 + 4.0 * kUnit);
  const double ka = kappa * g.anchor_max * (1.0 + 4.0 * kUnit);
  for (int k = 0; k < 100; ++k) {
    const double U = nu / root_sigma;
    const double W = nu * wide;
    // A spring's ends move by |u_i - u_j| <= |u_i| + |u_j| <= sqrt(2) |u|_2.
    const double delta = 1.4142135623730951 * (1.0 + 1e-15) * U;
    const double rho = delta / g.l0_min;
    if (!(rho <= 0.5)) {
      nu *= 0.5;
      continue;
    }
    // Step 4: the springs' nonlinear remainder, |R| <= kappa k_max c(rho) spread U^2 / l0,
    // entering u' and w' alike, where N(s R, s R) = s |R| exactly.
    const double c_nl = (2.0 + rho) * (2.0 + rho) /
                        (6.928203230275509 * (1.0 - rho) * (1.0 - rho)) * (1.0 + 1e-9);
    const double nonlinear = t.s * g.spread * kk * c_nl * U * U / g.l0_min;
    // Step 5: rounding of one step, per coordinate e_c, over every coordinate.
    const double d2 = (g.degree + 2.0) * (g.degree + 2.0);
    const double force_err = kUnit * d2 * (kk + ka) * (16.0 * g.l0_max + 64.0 * U);
    const double force_max = 3.0 * (ka + 2.0 * g.degree * kk) * U + force_err;
    const double e_c = 4.0 * (t.s * force_err +
                              kUnit * (4.0 * t.s * force_max + 6.0 * W + g.x_max + U)) +
                       1e-300;
    const double rounding = q * sqrt(g.coords) * e_c;
    if ((nonlinear + rounding) * (1.0 + 1e-9) <= contraction * nu) {
      const double r = nu * widen * (1.0 - 1e-9);
      t.nu_sq = r * r * (1.0 - 1e-9);
      t.u_max_sq = t.nu_sq / (root_sigma * root_sigma);
      return t;
    }
    // Too wide: the nonlinear term grows as nu^2, so shrink to where it would just fit (the
    // next pass checks it), or by a tenth where that gives no smaller radius.
    const double fit = (contraction * nu - rounding) / nonlinear;
    nu *= fit > 0 && fit < 0.999 ? fit * (1.0 - 1e-6) : 0.9;
  }
  return t;
}

/// N^2 of the state (positions x(i, c), velocities v(i, c)) plus a bound on its rounding: the
/// state lies in the trial's invariant ball when this is at most nu^2. A fixed node away from
/// its rest position (a hand-moved one) gives +inf, a non-finite value NaN.
template <class Pos, class Vel>
DAMPBOUND_HD double norm_bound(const SceneArrays& g, const TrialBound& t, Pos x, Vel v) {
  constexpr double inf = __builtin_huge_val();
  double n2 = 0, mag = 0;  // N^2 and the sum of the magnitudes of its terms
  const double s = t.s, b = t.b, dt = t.dt;
  for (int i = 0; i < g.nodes; ++i) {
    const double* X = g.rest + 3 * i;
    if (g.fixed[i]) {
      for (int c = 0; c < 3; ++c)
        if (x(i, c) != X[c]) return inf;
      continue;
    }
    const double ka = t.kappa * g.anchor_scale[i];
    for (int c = 0; c < 3; ++c) {
      const double u = x(i, c) - X[c];
      const double w = dt * v(i, c);
      const double p = u - w;
      // The anchor's part of (u - w)^T A^ u, then b u.w + (1 - b) w.w.
      n2 += s * (ka * (p * u)) + (b * (u * w) + (1.0 - b) * (w * w));
      mag += s * (ka * fabs(p * u)) + (b * fabs(u * w) + w * w);
    }
  }
  for (int k = 0; k < g.springs; ++k) {
    const int i = g.spring_i[k], j = g.spring_j[k];
    const double* Xi = g.rest + 3 * i;
    const double* Xj = g.rest + 3 * j;
    double dir[3];
    rest_direction(g, k, dir);
    double du = 0, dp = 0, au = 0, ap = 0;  // d.(u_i - u_j), d.(p_i - p_j) and magnitudes
    for (int c = 0; c < 3; ++c) {
      const double d = dir[c];
      const double ui = g.fixed[i] ? 0.0 : x(i, c) - Xi[c];
      const double uj = g.fixed[j] ? 0.0 : x(j, c) - Xj[c];
      const double pi = g.fixed[i] ? 0.0 : ui - dt * v(i, c);
      const double pj = g.fixed[j] ? 0.0 : uj - dt * v(j, c);
      du += d * (ui - uj);
      dp += d * (pi - pj);
      au += fabs(d) * (fabs(ui) + fabs(uj));
      ap += fabs(d) * (fabs(pi) + fabs(pj));
    }
    const double ks = t.kappa * g.kappa_scale[k];
    n2 += s * (ks * (du * dp));
    mag += s * (ks * (au * ap));
  }
  const double eps = 2.0 * kUnit * (3.0 * g.nodes + g.springs + 64.0);
  return n2 + eps * mag;
}

/// When to look again after a state outside the ball (N^2 bound `n2`) at `iteration`: the
/// iteration where the linear step's decay, (1 - b) per step in N^2, would bring it to nu^2;
/// at least the next one, at most `limit`. Only a schedule: a look that fails schedules
/// another, and the proof never depends on it. Multiplications only, so that the host and the
/// GPU round alike.
DAMPBOUND_HD inline int next_look(double n2, const TrialBound& t, int iteration, int limit) {
  const double ratio = t.nu_sq / n2;
  const double decay = 1.0 - t.b;
  double p = 1;
  int k = 0;
  while (p > ratio && iteration + k < limit) {
    p *= decay;
    ++k;
  }
  return iteration + (k < 1 ? 1 : k);
}

/// SPEC 8's early stop, the one rule for every runner: a run judged `running` under the
/// settled rule that has been below the band since `below_since` (> 0), at an iteration at or
/// past `next` (the run's own schedule, 0 at its start) where its largest displacement could
/// lie in the ball, is settled when `norm()` (norm_bound of its state) is at most nu^2; else
/// `next` moves on (next_look). Returns the verdict
/// (`verdict` unchanged where not proven).
template <class Norm>
DAMPBOUND_HD Outcome early_verdict(const StopRules& rules, Outcome verdict, int below_since,
                                   int iteration, double max_displacement, const TrialBound& t,
                                   int& next, Norm norm) {
  // Before the first look the largest displacement must be half the ball's radius:
  // on the paper plane N is 4 to 9 times sqrt(sigma) max_i |u_i| once the wave has spread,
  // so an earlier look would fail and cost a step's time for nothing.
  const double spread = next == 0 ? 4.0 : 1.0;
  if (verdict != Outcome::running || rules.rule != StopRule::settled || below_since == 0 ||
      !(t.nu_sq > 0) || iteration < next ||
      !(spread * max_displacement * max_displacement <= t.u_max_sq))
    return verdict;
  const double n2 = norm();
  if (n2 <= t.nu_sq) return Outcome::settled;
  next = next_look(n2, t, iteration, rules.max_iterations);
  return verdict;
}

}  // namespace dampbound::settle
