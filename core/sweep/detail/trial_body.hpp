#pragma once
// One sweep trial's step as one function for the host and the GPU (DAMPBOUND_HD,
// include/dampbound/physics/host_device.hpp): the batched kernel's arithmetic (core/sweep/detail/kernel_body.cpp),
// which is step()'s (core/physics/step.cpp, forces.cpp, bounds.cpp, integrate.cpp) operation by
// operation, written for one trial in plain doubles, plus what the batched kernel leaves to
// step(): SPEC 10's dashpot and Rayleigh damping (trial_terms.hpp). The GPU sweep (gpu/) runs
// one trial per device thread through it; core/sweep/flat_model.cpp builds its inputs and runs
// its host copy, which the tests compare bit for bit with the batched kernel and step().
//
// Only plain data crosses: the scene as flat arrays (FlatModel), a trial's constants
// (TrialConsts) and its state (TrialView), whose element k of an array lies at [k * stride]:
// stride 1 for one trial on the host, the number of trials on the GPU, where neighbouring
// threads then read neighbouring doubles.
#include <cfloat>
#include <cmath>
#include <cstddef>

#include "core/physics/detail/spring_block.hpp"
#include "core/sweep/detail/trial_terms.hpp"
#include "dampbound/physics/host_device.hpp"
#include "dampbound/physics/params.hpp"
#include "dampbound/run/verdict.hpp"

namespace dampbound::trial_body {

/// What a trial's step does for each node: per-lane safe-bound accumulators (SPEC 9: K_ii's
/// upper triangle and three off-diagonal row sums) or SPEC 10's gamma_safe_i.
constexpr int kSafePerNode = 9;

/// A trial's state: positions, velocities and internal forces (3 per node), SPEC 10's damping
/// force D' (3 per node, used when the trial has such damping), the safe policy's per-node
/// accumulators (kSafePerNode per node). Element k of each at [k * stride].
struct TrialView {
  double* x;
  double* v;
  double* f;
  double* damping;
  double* safe;
  std::size_t stride;
};

/// One step's counts (node-steps, springs) and max_i |x_i - X_i|^2 over finite values.
struct StepTally {
  long long violating = 0, unstabilisable = 0, clamped = 0, zero_length = 0;
  double max_sq = 0;
  bool bad = false;  // some |x_i - X_i| not finite
};

/// A trial in progress: its constants, result so far and band history (SPEC 8).
struct TrialSlot {
  TrialConsts p;
  TrialResult r;
  BandHistory band;
  settle::TrialBound bound;  ///< SPEC 8's early stop (core/run/detail/settle_bound.hpp)
  int next_look = 0;         ///< the proof's next look (settle::early_verdict)
};

/// forces.cpp's anchor term -kappa_a,i (x_i - X_i) of every node: F at the start of a step.
DAMPBOUND_HD inline void anchor_forces(const FlatModel& M, const TrialConsts& P,
                                       const TrialView& s) {
  const std::size_t w = s.stride;
  for (int i = 0; i < M.nodes; ++i) {
    const double nak = -(P.kappa * M.anchor_scale[i]);
    for (int c = 0; c < 3; ++c) {
      const int k = 3 * i + c;
      s.f[k * w] = nak * (s.x[k * w] - M.rest[k]);
    }
  }
}

/// The scene's initial state (perturbed positions and velocities) and its anchor forces.
DAMPBOUND_HD inline void trial_begin(const FlatModel& M, TrialSlot& slot, const TrialView& s) {
  const std::size_t w = s.stride;
  for (int k = 0; k < 3 * M.nodes; ++k) {
    s.x[k * w] = M.x0[k];
    s.v[k * w] = M.v0[k];
  }
  anchor_forces(M, slot.p, s);
  slot.r = TrialResult{};
  slot.band = BandHistory{};
  slot.next_look = 0;
  const TrialConsts& P = slot.p;
  slot.bound = P.damped ? settle::TrialBound{}
                        : settle::trial_bound(M.settle, P.m, P.kappa, P.gamma, P.dt,
                                              M.rules.restore_fraction * M.rules.reference);
}

/// forces.cpp: springs in list order, F_i += f, F_j -= f; a spring of zero (or NaN) length
/// has no direction: skipped and counted.
DAMPBOUND_HD inline long long spring_forces(const FlatModel& M, const TrialConsts& P,
                                            const TrialView& s) {
  const std::size_t w = s.stride;
  long long zero_length = 0;
  for (int k = 0; k < M.springs; ++k) {
    const int i = M.spring_i[k], j = M.spring_j[k];
    const double xi[3] = {s.x[(3 * i) * w], s.x[(3 * i + 1) * w], s.x[(3 * i + 2) * w]};
    const double xj[3] = {s.x[(3 * j) * w], s.x[(3 * j + 1) * w], s.x[(3 * j + 2) * w]};
    double e[3];
    const double length = spring_vector(xi, xj, e);
    if (!(length > 0)) {
      ++zero_length;
      continue;
    }
    const double scale = ((P.kappa * M.kappa_scale[k]) * (length - M.rest_length[k])) / length;
    const double f[3] = {scale * e[0], scale * e[1], scale * e[2]};
    for (int c = 0; c < 3; ++c) {
      s.f[(3 * i + c) * w] = s.f[(3 * i + c) * w] + f[c];
      s.f[(3 * j + c) * w] = s.f[(3 * j + c) * w] - f[c];
    }
  }
  return zero_length;
}

/// Node i's m_i, m_i/dt, gamma_lo_i (eq. 5) and user gamma_i as compile_model() and
/// upper_bound() round them: the trial's own when the scales are uniform.
struct NodeValues {
  double mass, md, lo, gu;
};

DAMPBOUND_HD inline NodeValues node_values(const FlatModel& M, const TrialConsts& P, int i) {
  if (M.uniform) return {P.mass, P.md, P.lo, P.gu};
  NodeValues q;
  q.mass = P.m * M.mass_scale[i];
  q.md = q.mass / P.dt;
  q.lo = 2.0 * sqrt(q.mass * (P.kappa * M.kappa_max_scale[i]));
  q.gu = P.gamma * M.gamma_scale[i];
  return q;
}

/// SPEC 4's effective gamma of a free node (bounds.cpp effective_damping), given gamma_hi
/// `hi` and, for the safe policy, gamma_safe `safe`.
DAMPBOUND_HD inline double effective_gamma(DampingPolicy policy, const NodeValues& q, double hi,
                                           double factor, double safe) {
  constexpr double inf = __builtin_huge_val();
  switch (policy) {
    case DampingPolicy::fixed:
      return q.gu;
    case DampingPolicy::clamp:
      return q.lo > hi ? hi : (q.gu < q.lo ? q.lo : (hi < q.gu ? hi : q.gu));
    case DampingPolicy::upper:
      return hi == inf ? 0.0 : factor * hi;
    case DampingPolicy::lower:
      return q.lo;
    case DampingPolicy::safe:
      return q.lo > safe ? (safe < 0.0 ? 0.0 : safe)
                         : (q.gu < q.lo ? q.lo : (safe < q.gu ? safe : q.gu));
  }
  return q.gu;
}

/// step.cpp + bounds.cpp + integrate.cpp for every node, the displacement after the step, and
/// the anchor part of the next step's force (forces.cpp).
DAMPBOUND_HD inline void node_pass(const FlatModel& M, const TrialConsts& P, const TrialView& s,
                                   StepTally& t) {
  constexpr double inf = __builtin_huge_val();
  const std::size_t w = s.stride;
  const bool safe_policy = M.policy == DampingPolicy::safe;
  for (int i = 0; i < M.nodes; ++i) {
    double* x = s.x + (3 * i) * w;
    double* v = s.v + (3 * i) * w;
    double* f = s.f + (3 * i) * w;
    if (!M.fixed[i]) {
      const NodeValues q = node_values(M, P, i);
      // F_i less SPEC 10's D'_i where the trial has such damping (step.cpp).
      double net[3];
      for (int c = 0; c < 3; ++c)
        net[c] = P.damped ? f[c * w] - s.damping[(3 * i + c) * w] : f[c * w];
      // Paper eq. 6: gamma_hi = |v m/dt + F| / |v|, +inf when |v| = 0.
      const double speed = sqrt((v[0] * v[0] + v[w] * v[w]) + v[2 * w] * v[2 * w]);
      const double w0 = v[0] * q.md + net[0];
      const double w1 = v[w] * q.md + net[1];
      const double w2 = v[2 * w] * q.md + net[2];
      const double wn = sqrt((w0 * w0 + w1 * w1) + w2 * w2);
      const double hi = speed == 0 ? inf : wn / speed;
      double safe = inf;
      if (safe_policy)
        safe = P.damped ? s.safe[(kSafePerNode * i) * w]
                        : safe_gamma_nodal(s.safe + (kSafePerNode * i) * w, w, q.mass, P.dt);
      const double g = effective_gamma(M.policy, q, hi, P.factor, safe);
      const bool unstab = q.lo > hi;
      const bool viol = g < q.lo || g > hi;
      t.violating += viol;
      t.unstabilisable += unstab;
      t.clamped += !unstab && !viol && g != q.gu;
      // integrate.cpp: a = (F - gamma v + f)/m, then eqs. 3-4 (or forward Euler).
      for (int c = 0; c < 3; ++c) {
        const double a = ((net[c] - g * v[c * w]) + M.ext[3 * i + c]) / q.mass;
        if (M.semi_implicit) {
          v[c * w] = v[c * w] + a * P.dt;
          x[c * w] = x[c * w] + v[c * w] * P.dt;
        } else {
          x[c * w] = x[c * w] + v[c * w] * P.dt;
          v[c * w] = v[c * w] + a * P.dt;
        }
      }
    }
    // step.cpp: |x_i - X_i| after the step; sqrt is monotonic, so the max of the squares
    // gives the max displacement, and a square is finite exactly when its root is.
    const double* X = M.rest + 3 * i;
    const double e0 = x[0] - X[0], e1 = x[w] - X[1], e2 = x[2 * w] - X[2];
    const double sq = (e0 * e0 + e1 * e1) + e2 * e2;
    t.max_sq = sq > t.max_sq ? sq : t.max_sq;
    t.bad = t.bad || !(sq <= DBL_MAX);
    const double nak = -(P.kappa * M.anchor_scale[i]);
    f[0] = nak * e0;
    f[w] = nak * e1;
    f[2 * w] = nak * e2;
  }
}

/// One step of the trial (step.cpp), its counts added to slot.r, then the protocol's verdict
/// (judge_band). Returns whether the trial is over.
DAMPBOUND_HD inline bool trial_step(const FlatModel& M, TrialSlot& slot, const TrialView& s) {
  const TrialConsts& P = slot.p;
  StepTally t;
  t.zero_length = spring_forces(M, P, s);
  if (P.damped) damping_forces(M, P, s.x, s.v, s.damping, s.stride);
  if (M.policy == DampingPolicy::safe) {
    if (P.damped)
      damped_safe_gammas(M, P, s.x, s.safe, kSafePerNode, s.stride);
    else
      safe_row_sums(M, P, s.x, s.safe, kSafePerNode, s.stride);
  }
  node_pass(M, P, s, t);
  TrialResult& r = slot.r;
  r.violations += t.violating;
  r.unstabilisable += t.unstabilisable;
  r.clamped += t.clamped;
  r.zero_length_springs += t.zero_length;
  ++r.iterations;
  // judge_band() (include/dampbound/run/verdict.hpp), with step.cpp's max displacement (inf when not finite).
  const bool finite = !t.bad;
  const double d = finite ? sqrt(t.max_sq) : __builtin_huge_val();
  r.max_displacement = d;
  r.outcome = judge_band(M.rules, slot.band, r.iterations, d, finite);
  // SPEC 8's early stop, as Session and the batched kernel decide it.
  const std::size_t w = s.stride;
  r.outcome = settle::early_verdict(
      M.rules, r.outcome, slot.band.below_since, r.iterations, d, slot.bound, slot.next_look,
      [&] {
        settle::SceneArrays g;
        g.nodes = M.nodes;
        g.springs = M.springs;
        g.spring_i = M.spring_i;
        g.spring_j = M.spring_j;
        g.kappa_scale = M.kappa_scale;
        g.rest = M.rest;
        g.anchor_scale = M.anchor_scale;
        g.fixed = M.fixed;
        return settle::norm_bound(
            g, slot.bound,
            [&](int i, int c) { return s.x[static_cast<std::size_t>(3 * i + c) * w]; },
            [&](int i, int c) { return s.v[static_cast<std::size_t>(3 * i + c) * w]; });
      });
  r.first_entry = slot.band.first_entry;
  r.left_at = slot.band.left_at;
  if (r.outcome == Outcome::settled) r.settled_at = slot.band.below_since;
  return r.outcome != Outcome::running;
}

/// Steps the trial until its verdict or `max_steps` steps; returns whether it is over.
DAMPBOUND_HD inline bool trial_advance(const FlatModel& M, TrialSlot& slot, const TrialView& s,
                                       int max_steps) {
  for (int k = 0; k < max_steps; ++k)
    if (trial_step(M, slot, s)) return true;
  return false;
}

}  // namespace dampbound::trial_body
