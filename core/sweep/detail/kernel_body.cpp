// The batched sweep kernel. Every formula below is step()'s (core/physics/step.cpp, forces.cpp,
// bounds.cpp, integrate.cpp), written lane-wise with the operands in the same order, so each
// lane rounds exactly as step() does on that lane's trial.
//
// Compiled once as it is (the generic variant) and once more per instruction set by a wrapper
// (core/sweep/detail/kernel_avx2.cpp, core/sweep/detail/kernel_avx512.cpp) that includes this file under a
// target pragma; everything here has internal linkage, and only the factory at the end is
// named after the variant (core/sweep/detail/kernel_body.hpp).
#include "core/sweep/kernel.hpp"

#include <cfloat>
#include <cmath>
#include <stdexcept>

#include "core/physics/detail/simd.hpp"
#include "core/physics/detail/spring_block.hpp"
#include "core/run/settle_proof.hpp"
#include "core/sweep/detail/kernel_body.hpp"
#include "core/sweep/detail/lanes.hpp"
#include "core/sweep/trials.hpp"
#include "dampbound/run/session.hpp"

#ifndef DAMPBOUND_KERNEL_VARIANT
#define DAMPBOUND_KERNEL_VARIANT kernel_generic
#endif

namespace dampbound {

using simd::splat;
using simd::vd;
using simd::vl;
using namespace sweep_lanes;

static_assert(simd::kLanes <= BatchKernel::kLanes, "one lane per trial");

namespace {

/// Counts of one step, per lane.
struct StepCounts {
  vl violating, unstabilisable, clamped, zero_length;
  vd max_sq;  // max_i |x_i - X_i|^2 over finite values
  vl bad;     // some |x_i - X_i| not finite
};

bool all_equal(const std::vector<double>& v) {
  for (double x : v)
    if (x != v.front()) return false;
  return true;
}

struct Kernel final : BatchKernel::Impl {
  static constexpr int kLanes = simd::kLanes;
  size_t n = 0;
  DampingPolicy policy;
  StopRules rules;
  bool semi_implicit = true;
  bool uniform = true;
  std::vector<SpringData> springs;
  std::vector<double> rest, x0, v0, ext;  // 3 per node
  std::vector<double> anchor_scale, mass_scale, gamma_scale, kappa_max_scale;
  std::vector<unsigned char> fixed;
  std::vector<NodeBlock> blocks;
  std::vector<NodeParams> node_params;  // only when !uniform
  std::vector<SafeBlock> safe_blocks;   // only for the safe policy
  // Per-lane parameters.
  vd m, kappa, gamma, dt, factor;
  vd mass, md, lo, gu;  // uniform scales: the same for every node
  // Per-lane trial bookkeeping.
  bool active[kLanes] = {};
  std::size_t id[kLanes] = {};
  TrialResult result[kLanes];
  BandHistory band[kLanes];
  // SPEC 8's early stop (core/run/settle_proof.hpp): the scene's proof, each lane's bound.
  std::unique_ptr<SettleProof> proof;
  settle::SceneArrays proof_arrays;
  settle::TrialBound bound[kLanes];
  int next_look[kLanes] = {};

  Kernel(const SceneSpec& scene, DampingPolicy pol, const StopRules& r) : policy(pol), rules(r) {
    if (const auto why = batch_kernel_unsupported(scene))
      throw std::invalid_argument("batched kernel: " + *why);
    semi_implicit = scene.params.integrator == Integrator::semi_implicit_euler;
    const ModelSpec& mo = scene.model;
    n = mo.rest.size();
    const State s0 = initial_state(scene);
    rest.resize(3 * n);
    x0.resize(3 * n);
    v0.resize(3 * n);
    ext.resize(3 * n);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        rest[3 * i + c] = mo.rest[i][c];
        x0[3 * i + c] = s0.x[i][c];
        v0[3 * i + c] = s0.v[i][c];
        ext[3 * i + c] = mo.external_force[i][c];
      }
    anchor_scale = mo.anchor_scale;
    mass_scale = mo.mass_scale;
    gamma_scale = mo.gamma_scale;
    fixed = mo.fixed;
    // kappa_i of eq. 5 = max incident stiffness = kappa * (max incident scale): x -> kappa*x
    // rounds monotonically, so the max of the products is the product of the max.
    kappa_max_scale = anchor_scale;
    for (int k : spring_schedule(mo)) {
      const Spring& sp = mo.springs[static_cast<size_t>(k)];
      springs.push_back({sp.i, sp.j, sp.rest_length, sp.kappa_scale});
      auto& a = kappa_max_scale[static_cast<size_t>(sp.i)];
      auto& b = kappa_max_scale[static_cast<size_t>(sp.j)];
      a = std::max(a, sp.kappa_scale);
      b = std::max(b, sp.kappa_scale);
    }
    uniform =
        n > 0 && all_equal(mass_scale) && all_equal(gamma_scale) && all_equal(kappa_max_scale);
    blocks.resize(n);
    if (!uniform) node_params.resize(n);
    if (policy == DampingPolicy::safe) safe_blocks.resize(n);
    if (rules.rule == StopRule::settled) {
      proof = std::make_unique<SettleProof>(mo, x0, v0, scene.params.integrator, policy, false,
                                            !scene.cuts.empty());
      if (proof->why_not())
        proof.reset();
      else
        proof_arrays = proof->arrays();
    }
    for (int l = 0; l < kLanes; ++l) park(l);
  }

  /// A lane without a trial: at rest, no stiffness, so it stays finite and cheap.
  void park(int l) {
    active[l] = false;
    TrialParams p;
    p.m = 1;
    p.kappa = 0;
    p.gamma = 0;
    p.dt = 1e-3;
    p.factor = 0;
    set_lane(l, p, rest);
  }

  void load(int l, std::size_t trial, const TrialParams& p) {
    set_lane(l, p, x0);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) blocks[i].v[c][l] = v0[3 * i + c];
    active[l] = true;
    id[l] = trial;
    result[l] = TrialResult{};
    band[l] = BandHistory{};
    const bool other_damping = (p.kd && *p.kd != 0) || (p.rayleigh_mass && *p.rayleigh_mass != 0) ||
                               (p.rayleigh_stiffness && *p.rayleigh_stiffness != 0);
    next_look[l] = 0;
    bound[l] = proof && !other_damping ? proof->trial(p.m, p.kappa, p.gamma, p.dt, rules)
                                       : settle::TrialBound{};
  }

  void set_lane(int l, const TrialParams& p, const std::vector<double>& x) {
    m[l] = p.m;
    kappa[l] = p.kappa;
    gamma[l] = p.gamma;
    dt[l] = p.dt;
    factor[l] = p.factor;
    // compile_model() and upper_bound(): m_i = m*scale, m_i/dt, 2 sqrt(m_i kappa_i).
    // Lane l of each vector is assigned one by one: Clang does not bind a reference to a
    // vector element.
    auto node_values = [&](size_t i, vd& ms, vd& mds, vd& los, vd& gus) {
      ms[l] = p.m * mass_scale[i];
      mds[l] = ms[l] / p.dt;
      los[l] = 2.0 * std::sqrt(ms[l] * (p.kappa * kappa_max_scale[i]));
      gus[l] = p.gamma * gamma_scale[i];
    };
    if (n > 0 && uniform) node_values(0, mass, md, lo, gu);
    for (size_t i = 0; i < n; ++i) {
      NodeBlock& b = blocks[i];
      // forces.cpp: F_i starts as the anchor force -kappa_a,i (x_i - X_i).
      const double nak = -(p.kappa * anchor_scale[i]);
      for (int c = 0; c < 3; ++c) {
        b.x[c][l] = x[3 * i + c];
        b.v[c][l] = 0;
        b.f[c][l] = nak * (x[3 * i + c] - rest[3 * i + c]);
      }
      if (!uniform) {
        NodeParams& q = node_params[i];
        node_values(i, q.mass, q.md, q.lo, q.gu);
      }
    }
  }

  /// forces.cpp: springs in list order; F_i += f, F_j -= f; a spring of zero (or NaN)
  /// length is skipped and counted.
  vl spring_pass() {
    vl zero_length = simd::splat_int(0);
    NodeBlock* bl = blocks.data();
    for (const SpringData& s : springs) {
      NodeBlock& bi = bl[s.i];
      NodeBlock& bj = bl[s.j];
      vd e[3];
      const vd length = spring_vector(bi.x, bj.x, e, simd::Sqrt{});
      const vl ok = length > 0;
      const vd scale = ((kappa * s.kappa_scale) * (length - s.rest_length)) / length;
      const vd f0 = scale * e[0], f1 = scale * e[1], f2 = scale * e[2];
      bi.f[0] = ok ? bi.f[0] + f0 : bi.f[0];
      bi.f[1] = ok ? bi.f[1] + f1 : bi.f[1];
      bi.f[2] = ok ? bi.f[2] + f2 : bi.f[2];
      bj.f[0] = ok ? bj.f[0] - f0 : bj.f[0];
      bj.f[1] = ok ? bj.f[1] - f1 : bj.f[1];
      bj.f[2] = ok ? bj.f[2] - f2 : bj.f[2];
      zero_length += ok + 1;  // ok is -1 (true) or 0
    }
    return zero_length;
  }

  /// step.cpp + bounds.cpp + integrate.cpp for every node, then the displacement after the
  /// step, then the anchor part of the next step's force (forces.cpp).
  template <DampingPolicy P, bool SemiImplicit, bool Uniform>
  void node_pass(StepCounts& sc) {
    const vd inf = splat(HUGE_VAL);
    const vd zero = splat(0.0);
    const vd big = splat(DBL_MAX);
    vl violating = simd::splat_int(0), unstabilisable = violating, clamped = violating;
    vd max_sq = zero;
    vl bad = violating;
    for (size_t i = 0; i < n; ++i) {
      NodeBlock& b = blocks[i];
      const double* X = &rest[3 * i];
      if (!fixed[i]) {
        vd mass_i, md_i, lo_i, gu_i;
        if constexpr (Uniform) {
          mass_i = mass, md_i = md, lo_i = lo, gu_i = gu;
        } else {
          const NodeParams& q = node_params[i];
          mass_i = q.mass, md_i = q.md, lo_i = q.lo, gu_i = q.gu;
        }
        // Paper eq. 6: gamma_hi = |v m/dt + F| / |v|, +inf when |v| = 0.
        const vd speed = simd::sqrt((b.v[0] * b.v[0] + b.v[1] * b.v[1]) + b.v[2] * b.v[2]);
        const vd w0 = b.v[0] * md_i + b.f[0];
        const vd w1 = b.v[1] * md_i + b.f[1];
        const vd w2 = b.v[2] * md_i + b.f[2];
        const vd wn = simd::sqrt((w0 * w0 + w1 * w1) + w2 * w2);
        const vd hi = speed == 0 ? inf : wn / speed;
        // SPEC 4: the policy's effective gamma (bounds.cpp effective_damping).
        const vl unstab = lo_i > hi;
        vd g;
        if constexpr (P == DampingPolicy::fixed) {
          g = gu_i;
        } else if constexpr (P == DampingPolicy::clamp) {
          const vd clamped_g = gu_i < lo_i ? lo_i : (hi < gu_i ? hi : gu_i);
          g = unstab ? hi : clamped_g;
        } else if constexpr (P == DampingPolicy::upper) {
          g = hi == inf ? zero : factor * hi;
        } else if constexpr (P == DampingPolicy::safe) {
          g = safe_damping(safe_blocks[i], mass_i, dt, lo_i, gu_i);
        } else {
          g = lo_i;
        }
        const vl viol = (g < lo_i) | (g > hi);
        violating -= viol;
        unstabilisable -= unstab;
        if constexpr (P != DampingPolicy::fixed) clamped -= ~unstab & ~viol & (g != gu_i);
        // integrate.cpp: a = (F - gamma v + f)/m, then eqs. 3-4 (or forward Euler).
        for (int c = 0; c < 3; ++c) {
          const vd a = ((b.f[c] - g * b.v[c]) + ext[3 * i + c]) / mass_i;
          if constexpr (SemiImplicit) {
            b.v[c] = b.v[c] + a * dt;
            b.x[c] = b.x[c] + b.v[c] * dt;
          } else {
            b.x[c] = b.x[c] + b.v[c] * dt;
            b.v[c] = b.v[c] + a * dt;
          }
        }
      }
      // step.cpp: |x_i - X_i| after the step; sqrt is monotonic, so the max of the squares
      // gives the max displacement, and a square is finite exactly when its root is.
      const vd e0 = b.x[0] - X[0], e1 = b.x[1] - X[1], e2 = b.x[2] - X[2];
      const vd sq = (e0 * e0 + e1 * e1) + e2 * e2;
      max_sq = sq > max_sq ? sq : max_sq;
      bad |= ~(sq <= big);
      const vd nak = -(kappa * anchor_scale[i]);
      b.f[0] = nak * e0;
      b.f[1] = nak * e1;
      b.f[2] = nak * e2;
    }
    sc.violating = violating;
    sc.unstabilisable = unstabilisable;
    sc.clamped = clamped;
    sc.max_sq = max_sq;
    sc.bad = bad;
  }

  template <DampingPolicy P>
  void node_pass_p(StepCounts& sc) {
    if (semi_implicit) {
      if (uniform)
        node_pass<P, true, true>(sc);
      else
        node_pass<P, true, false>(sc);
    } else {
      if (uniform)
        node_pass<P, false, true>(sc);
      else
        node_pass<P, false, false>(sc);
    }
  }

  void step(StepCounts& sc) {
    sc.zero_length = spring_pass();
    switch (policy) {
      case DampingPolicy::fixed:
        node_pass_p<DampingPolicy::fixed>(sc);
        break;
      case DampingPolicy::clamp:
        node_pass_p<DampingPolicy::clamp>(sc);
        break;
      case DampingPolicy::upper:
        node_pass_p<DampingPolicy::upper>(sc);
        break;
      case DampingPolicy::lower:
        node_pass_p<DampingPolicy::lower>(sc);
        break;
      case DampingPolicy::safe:
        if (uniform)
          safe_pass<true>(springs, blocks, node_params, fixed, anchor_scale, kappa, mass,
                          safe_blocks);
        else
          safe_pass<false>(springs, blocks, node_params, fixed, anchor_scale, kappa, mass,
                           safe_blocks);
        node_pass_p<DampingPolicy::safe>(sc);
        break;
    }
  }

  std::uint64_t run(const TrialSource& source, const TrialSink& sink,
                    const std::atomic<bool>* cancel) override {
    auto refill = [&](int l) {
      std::size_t trial = 0;
      TrialParams p;
      if (source(trial, p))
        load(l, trial, p);
      else
        park(l);
    };
    for (int l = 0; l < kLanes; ++l) refill(l);
    std::uint64_t lane_steps = 0;
    StepCounts sc;
    for (;;) {
      int live = 0;
      for (int l = 0; l < kLanes; ++l) live += active[l];
      if (live == 0) break;
      if (cancel && cancel->load(std::memory_order_relaxed)) break;
      step(sc);
      lane_steps += static_cast<std::uint64_t>(live);
      const vd max_d = simd::sqrt(sc.max_sq);
      for (int l = 0; l < kLanes; ++l) {
        if (!active[l]) continue;
        TrialResult& r = result[l];
        r.violations += sc.violating[l];
        r.unstabilisable += sc.unstabilisable[l];
        r.clamped += sc.clamped[l];
        r.zero_length_springs += sc.zero_length[l];
        ++r.iterations;
        // judge_band() (include/dampbound/run/verdict.hpp), with step.cpp's max displacement (inf when not finite).
        const bool finite = sc.bad[l] == 0;
        const double d = finite ? max_d[l] : HUGE_VAL;
        r.max_displacement = d;
        r.outcome = judge_band(rules, band[l], r.iterations, d, finite);
        r.outcome = settle::early_verdict(
            rules, r.outcome, band[l].below_since, r.iterations, d, bound[l], next_look[l], [&] {
              return settle::norm_bound(
                  proof_arrays, bound[l],
                  [&](int i, int c) { return blocks[static_cast<size_t>(i)].x[c][l]; },
                  [&](int i, int c) { return blocks[static_cast<size_t>(i)].v[c][l]; });
            });
        r.first_entry = band[l].first_entry;
        r.left_at = band[l].left_at;
        if (r.outcome == Outcome::settled) r.settled_at = band[l].below_since;
        if (r.outcome != Outcome::running) {
          sink(id[l], r);
          refill(l);
        }
      }
    }
    return lane_steps;
  }

  long long spring_evaluations_per_step() const override {
    long long anchors = 0;
    for (double s : anchor_scale) anchors += s > 0;
    return static_cast<long long>(springs.size()) + anchors;
  }
};

}  // namespace

namespace DAMPBOUND_KERNEL_VARIANT {
std::unique_ptr<BatchKernel::Impl> make(const SceneSpec& scene, DampingPolicy policy,
                                        const StopRules& rules) {
  return std::make_unique<Kernel>(scene, policy, rules);
}
}  // namespace DAMPBOUND_KERNEL_VARIANT

}  // namespace dampbound
