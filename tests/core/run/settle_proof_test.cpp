// SPEC 8's early stop (core/run/settle_proof.cpp, core/run/detail/settle_bound.hpp; the proof
// in docs/settled.md): on thousands of trials of a paper plane (damping from a tenth of the
// lower bound to above it, stiffness across the stability limit, slow trials that enter the
// band late and leave it), the batched kernel with the proof gives every trial the verdict,
// first entry, exit, settled and divergence iterations of the same trial stepped to its
// limit; a widened (unsound) radius does not.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/run/settle_proof.hpp"
#include "core/sweep/kernel.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/run/scene.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound {
namespace {

StopRules settled_rules(int limit) {
  StopRules r;
  r.rule = StopRule::settled;
  r.max_iterations = limit;
  return r;
}

/// m in 3 values, kappa/m from 0.05 to 600 (the plane's stability limit at dt = 0.05 is near
/// 270), zeta from 0.1 to 1.2 (gamma = zeta x the lower bound), two time steps.
std::vector<TrialParams> sweep_trials() {
  std::vector<TrialParams> trials;
  for (double m : {0.001, 0.0037, 0.01})
    for (int k = 0; k < 44; ++k)
      for (double zeta : {0.1, 0.25, 0.4, 0.5, 0.7, 0.9, 1.0, 1.2})
        for (double dt : {0.05, 0.11}) {
          TrialParams t;
          t.m = m;
          t.kappa = m * 0.05 * std::pow(1.25, k);
          t.gamma = zeta * lower_bound(t.m, t.kappa);
          t.dt = dt;
          trials.push_back(t);
        }
  return trials;
}

std::vector<TrialResult> run_all(const SceneSpec& scene, const std::vector<TrialParams>& trials,
                                 const StopRules& rules) {
  BatchKernel kernel(scene, DampingPolicy::fixed, rules);
  std::vector<TrialResult> out(trials.size());
  std::size_t next = 0;
  kernel.run(
      [&](std::size_t& id, TrialParams& p) {
        if (next == trials.size()) return false;
        id = next;
        p = trials[next++];
        return true;
      },
      [&](std::size_t id, const TrialResult& r) { out[id] = r; });
  return out;
}

/// How many trials differ from `full` in outcome, first entry, exit, settled or divergence
/// iteration.
int differing(const std::vector<TrialResult>& full, const std::vector<TrialResult>& got) {
  int bad = 0;
  for (std::size_t k = 0; k < full.size(); ++k) {
    const TrialResult& a = full[k];
    const TrialResult& b = got[k];
    const bool diverged_differs =
        (a.outcome == Outcome::diverged || b.outcome == Outcome::diverged) &&
        a.iterations != b.iterations;
    bad += a.outcome != b.outcome || a.first_entry != b.first_entry || a.left_at != b.left_at ||
           a.settled_at != b.settled_at || diverged_differs;
  }
  return bad;
}

class SettleProofTest : public ::testing::Test {
 protected:
  void TearDown() override {
    set_settle_proof_enabled(true);
    set_settle_proof_widen(1.0);
  }
};

TEST_F(SettleProofTest, EarlyStopsGiveTheVerdictsOfRunningToTheLimit) {
  const SceneSpec scene = paper_plane_scene(12);
  const std::vector<TrialParams> trials = sweep_trials();
  const StopRules rules = settled_rules(800);
  set_settle_proof_enabled(false);
  const std::vector<TrialResult> full = run_all(scene, trials, rules);
  set_settle_proof_enabled(true);
  const std::vector<TrialResult> early = run_all(scene, trials, rules);
  ASSERT_GE(trials.size(), 2000u);
  EXPECT_EQ(differing(full, early), 0);
  // The sweep has every verdict, runs that entered and left, late entries and settled runs
  // the proof stopped early, most of them.
  int settled = 0, stopped = 0, diverged = 0, not_settled = 0, left = 0, late = 0;
  for (std::size_t k = 0; k < trials.size(); ++k) {
    const TrialResult& r = early[k];
    settled += r.outcome == Outcome::settled;
    stopped += r.outcome == Outcome::settled && r.iterations < rules.max_iterations;
    diverged += r.outcome == Outcome::diverged;
    not_settled += r.outcome == Outcome::not_settled;
    left += r.left_at > 0;
    late += r.first_entry > 400;
    if (r.outcome == Outcome::settled && r.iterations < rules.max_iterations) {
      EXPECT_GE(r.iterations, r.settled_at);
    }
  }
  EXPECT_GT(diverged, 100);
  EXPECT_GT(not_settled, 100);
  EXPECT_GT(left, 20);
  EXPECT_GT(late, 20);
  EXPECT_GT(settled, 500);
  EXPECT_GT(stopped, settled / 2);
  // A radius 100 times too wide stops runs that would leave the band: the comparison sees it.
  set_settle_proof_widen(100.0);
  const std::vector<TrialResult> wide = run_all(scene, trials, rules);
  EXPECT_GT(differing(full, wide), 0);
}

TEST_F(SettleProofTest, SessionStopsWhereTheKernelDoes) {
  SceneSpec scene = paper_plane_scene(12);
  const StopRules rules = settled_rules(800);
  TrialParams t;
  t.m = 0.001;
  t.kappa = 0.001;
  t.gamma = 0.5 * lower_bound(t.m, t.kappa);
  const TrialResult k = run_all(scene, {t}, rules)[0];
  Params p = scene.params;
  p.m = t.m;
  p.kappa = t.kappa;
  p.gamma = t.gamma;
  Session s(scene, p, rules);
  const RunResult& r = s.run_to_end();
  EXPECT_EQ(r.outcome, Outcome::settled);
  EXPECT_LT(r.iterations, rules.max_iterations);
  EXPECT_EQ(r.iterations, k.iterations);
  EXPECT_EQ(r.settled_at, k.settled_at);
  EXPECT_EQ(r.max_displacement, k.max_displacement);
}

TEST_F(SettleProofTest, SaysWhichScenesItDoesNotCover) {
  const SceneSpec scene = paper_plane_scene(6);
  const State s0 = initial_state(scene);
  std::vector<double> x0, v0;
  for (std::size_t i = 0; i < s0.x.size(); ++i)
    for (int c = 0; c < 3; ++c) x0.push_back(s0.x[i][c]), v0.push_back(s0.v[i][c]);
  const auto proof = [&](const ModelSpec& mo, DampingPolicy policy, Integrator in) {
    return SettleProof(mo, x0, v0, in, policy, false, false).why_not();
  };
  const Integrator paper = Integrator::semi_implicit_euler;
  EXPECT_FALSE(proof(scene.model, DampingPolicy::fixed, paper));
  EXPECT_EQ(*proof(scene.model, DampingPolicy::clamp, paper),
            "the policy chooses gamma from the state");
  EXPECT_EQ(*proof(scene.model, DampingPolicy::fixed, Integrator::forward_euler),
            "not the paper's step");
  ModelSpec heavy = scene.model;
  heavy.mass_scale[3] = 2;
  EXPECT_EQ(*proof(heavy, DampingPolicy::fixed, paper), "non-uniform masses");
  ModelSpec loose = scene.model;
  loose.anchor_scale[5] = 0;
  EXPECT_EQ(*proof(loose, DampingPolicy::fixed, paper), "a free node without an anchor");
  ModelSpec stressed = scene.model;
  stressed.springs[0].rest_length *= 0.9;
  EXPECT_EQ(*proof(stressed, DampingPolicy::fixed, paper),
            "a spring not at its rest length at rest");
}

TEST_F(SettleProofTest, NoCertificateWhereAModeIsOverDamped) {
  const SceneSpec scene = paper_plane_scene(6);
  const State s0 = initial_state(scene);
  std::vector<double> x0, v0;
  for (std::size_t i = 0; i < s0.x.size(); ++i)
    for (int c = 0; c < 3; ++c) x0.push_back(s0.x[i][c]), v0.push_back(s0.v[i][c]);
  const SettleProof proof(scene.model, x0, v0, Integrator::semi_implicit_euler,
                          DampingPolicy::fixed, false, false);
  const StopRules rules = settled_rules(1000);
  // zeta = 0.5 at kappa/m = 1, dt = 0.05: every mode under-damped, a radius.
  EXPECT_GT(proof.trial(0.001, 0.001, 0.5 * lower_bound(0.001, 0.001), 0.05, rules).nu_sq, 0);
  // zeta = 1.2: the anchors' mode is over-damped, no radius; no damping: none either.
  EXPECT_EQ(proof.trial(0.001, 0.001, 1.2 * lower_bound(0.001, 0.001), 0.05, rules).nu_sq, 0);
  EXPECT_EQ(proof.trial(0.001, 0.001, 0.0, 0.05, rules).nu_sq, 0);
  // Past the stability limit (kappa/m = 2000 at dt = 0.05): none.
  EXPECT_EQ(proof.trial(0.001, 2.0, 0.5 * lower_bound(0.001, 2.0), 0.05, rules).nu_sq, 0);
}

}  // namespace
}  // namespace dampbound
