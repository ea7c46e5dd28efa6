// The trial body's host copy (core/sweep/detail/trial_body.hpp through run_trial_body), the
// code the GPU sweep runs on the device, against the CPU's sweeps trial by trial and bit for
// bit: the batched kernel on nodal damping, step() (Session) on SPEC 10's dashpot and
// Rayleigh damping, every policy, both stop rules, both integrators, borderline trials.
#include "core/sweep/flat_model.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/sweep/trials.hpp"
#include "dampbound/physics/bounds.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

bool same_double_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

constexpr size_t kLeftSlot = 6;                // FlatSeen's extra slot: entered the band and left
using FlatSeen = std::array<long, kLeftSlot + 1>;  // per Outcome, and kLeftSlot

/// Trials compared so far in this test binary.
long g_compared = 0;

/// Names how many trials a test compared, in its output and its XML report.
struct CountTrials {
  long start = g_compared;
  ~CountTrials() {
    const long n = g_compared - start;
    ::testing::Test::RecordProperty("trials_compared", std::to_string(n));
    std::printf("[ trials   ] %ld compared bit for bit\n", n);
  }
};

/// Compares the trial body with `reference` on every trial; returns the outcomes seen.
template <class Reference>
FlatSeen expect_body_matches(const SceneSpec& scene, DampingPolicy policy, const StopRules& rules,
                         const std::vector<TrialParams>& trials, Reference reference) {
  const FlatScene flat(scene, policy, rules);
  const std::vector<TrialResult> body = run_trial_body(flat, trials);
  const std::vector<TrialResult> ref = reference(scene, policy, rules, trials);
  FlatSeen seen{};
  EXPECT_EQ(body.size(), ref.size());
  for (size_t k = 0; k < trials.size() && k < ref.size(); ++k) {
    const TrialResult& got = body[k];
    const TrialResult& want = ref[k];
    SCOPED_TRACE(scene.name + " " + to_string(policy) + " " + to_string(rules.rule) +
                 " m=" + std::to_string(trials[k].m) + " kappa=" + std::to_string(trials[k].kappa) +
                 " gamma=" + std::to_string(trials[k].gamma) +
                 " dt=" + std::to_string(trials[k].dt));
    EXPECT_EQ(std::string(to_string(got.outcome)), to_string(want.outcome));
    EXPECT_EQ(got.iterations, want.iterations);
    EXPECT_TRUE(same_double_bits(got.max_displacement, want.max_displacement))
        << got.max_displacement << " vs " << want.max_displacement;
    EXPECT_EQ(got.violations, want.violations);
    EXPECT_EQ(got.unstabilisable, want.unstabilisable);
    EXPECT_EQ(got.clamped, want.clamped);
    EXPECT_EQ(got.zero_length_springs, want.zero_length_springs);
    EXPECT_EQ(got.first_entry, want.first_entry);
    EXPECT_EQ(got.left_at, want.left_at);
    EXPECT_EQ(got.settled_at, want.settled_at);
    ++seen[static_cast<size_t>(want.outcome)];
    seen[kLeftSlot] += want.left_at > 0;
  }
  g_compared += static_cast<long>(trials.size());
  return seen;
}

std::vector<TrialResult> batched(const SceneSpec& scene, DampingPolicy policy,
                                 const StopRules& rules, const std::vector<TrialParams>& trials) {
  return run_batched(scene, policy, rules, trials);
}

std::vector<TrialResult> stepped(const SceneSpec& scene, DampingPolicy policy,
                                 const StopRules& rules, const std::vector<TrialParams>& trials) {
  std::vector<TrialResult> out;
  for (const TrialParams& t : trials) out.push_back(run_reference(scene, policy, rules, t));
  return out;
}

void add(FlatSeen& total, const FlatSeen& s) {
  for (size_t k = 0; k < total.size(); ++k) total[k] += s[k];
}

/// Every verdict of `rule` seen, and (settled rule) a run that entered the band and left.
void expect_every_verdict(const FlatSeen& seen, StopRule rule) {
  const bool settled = rule == StopRule::settled;
  EXPECT_GT(seen[static_cast<size_t>(settled ? Outcome::settled : Outcome::restored)], 0);
  EXPECT_GT(seen[static_cast<size_t>(Outcome::diverged)], 0);
  EXPECT_GT(seen[static_cast<size_t>(settled ? Outcome::not_settled : Outcome::not_restored)], 0);
}

/// The batched kernel test's irregular scene: non-uniform scales, partial anchors, an
/// external force, a fixed node, two coincident nodes joined by a spring of zero length.
SceneSpec irregular_flat_scene() {
  SceneSpec s;
  s.name = "irregular";
  ModelSpec& m = s.model;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 23; ++i) add_node(m, Vec3(u(rng) * 3, u(rng) * 0.5, u(rng) * 3));
  add_node(m, m.rest[5]);
  for (size_t i = 0; i < 24; ++i) {
    m.mass_scale[i] = 0.5 + u(rng);
    m.gamma_scale[i] = 0.5 + u(rng);
    if (i % 3 != 0) m.anchor_scale[i] = 0.2 + u(rng);
  }
  m.fixed[0] = 1;
  m.external_force[7] = Vec3(0, -0.0004, 0.0001);
  for (int i = 0; i < 23; ++i)
    for (int j = i + 1; j < 23; ++j)
      if (u(rng) < 0.18) add_spring(m, i, j, 0.3 + 2 * u(rng));
  add_spring(m, 5, 23, 1.0);
  add_spring(m, 23, 9, 1.0);
  for (size_t k = 0; k < m.springs.size(); ++k) m.springs[k].kd_scale = 0.5 + u(rng);
  s.params = default_params();
  s.perturbations.push_back({12, Vec3(0.2, 0.6, -0.1), Vec3::Zero()});
  s.perturbations.push_back({3, Vec3::Zero(), Vec3(0.1, 0.0, 0.3)});
  return s;
}

/// Random trials around the lower bound (zeta 0 .. 3) over kappa/m across the edge of
/// divergence at `dt`, factors 1 and 1.05.
std::vector<TrialParams> random_trials(int count, unsigned seed, double ratio_max, double dt) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<TrialParams> out;
  for (int k = 0; k < count; ++k) {
    TrialParams t;
    t.m = 0.0005 + 0.01 * u(rng);
    t.kappa = t.m * ratio_max * u(rng) * u(rng);
    t.gamma = 3 * u(rng) * lower_bound(t.m, t.kappa);
    t.dt = dt;
    t.factor = k % 2 ? 1.05 : 1.0;
    out.push_back(t);
  }
  return out;
}

TEST(TrialBody, SmallScenesEveryPolicyMatchTheBatchedKernel) {
  const CountTrials count;
  SceneSpec two = test::shipped_scene("two-node");
  SceneSpec irregular = irregular_flat_scene();
  SceneSpec euler = irregular_flat_scene();
  euler.name = "irregular-forward-euler";
  euler.params.integrator = Integrator::forward_euler;
  for (StopRule rule : {StopRule::first_entry, StopRule::settled}) {
    FlatSeen seen{};
    for (DampingPolicy p : kPolicies) {
      StopRules rules;
      rules.rule = rule;
      rules.reference = 0.5;
      rules.max_iterations = 300;
      add(seen, expect_body_matches(two, p, rules, random_trials(120, 3, 2000, 0.05), batched));
      rules.reference = 0.6;
      for (const SceneSpec* s : {&irregular, &euler})
        add(seen, expect_body_matches(*s, p, rules, random_trials(60, 5, 600, 0.02), batched));
    }
    expect_every_verdict(seen, rule);
    if (rule == StopRule::settled) {
      EXPECT_GT(seen[kLeftSlot], 0);
    }
  }
}

/// The paper's mesh (a small copy and the full one) with borderline trials: gamma around the
/// value that restores exactly at the limit, kappa/m across the edge of divergence.
TEST(TrialBody, PaperMeshBorderlineTrialsMatchTheBatchedKernel) {
  const CountTrials count;
  const SceneSpec small = paper_plane_scene(8);
  const SceneSpec full = test::shipped_scene("paper-plane");
  std::vector<TrialParams> edge;
  for (int k = 0; k <= 12; ++k) {
    TrialParams t;
    t.m = 0.001;
    t.kappa = 0.01;
    t.gamma = (0.30 + 0.01 * k) * lower_bound(t.m, t.kappa);
    edge.push_back(t);
  }
  for (double r : {100.0, 140.0, 160.0, 170.0, 175.0, 180.0, 190.0, 220.0, 400.0}) {
    TrialParams t;
    t.m = 0.0005;
    t.kappa = r * t.m;
    t.gamma = 0.25 * lower_bound(t.m, t.kappa);
    edge.push_back(t);
  }
  for (StopRule rule : {StopRule::first_entry, StopRule::settled}) {
    StopRules rules = full.rules;
    rules.rule = rule;
    rules.max_iterations = 60;
    FlatSeen seen = expect_body_matches(full, DampingPolicy::fixed, rules, edge, batched);
    for (DampingPolicy p : kPolicies) {
      rules.max_iterations = 150;
      add(seen, expect_body_matches(small, p, rules, random_trials(150, 9, 1000, 0.05), batched));
    }
    expect_every_verdict(seen, rule);
  }
}

/// SPEC 10's damping runs through step() on the CPU (the batched kernel applies nodal damping
/// only): the body must match Session bit for bit, the damped safe bound included.
TEST(TrialBody, DashpotAndRayleighTrialsMatchStep) {
  const CountTrials count;
  SceneSpec irregular = irregular_flat_scene();
  SceneSpec plane = paper_plane_scene(6);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<TrialParams> trials = random_trials(36, 17, 600, 0.02);
  for (size_t k = 0; k < trials.size(); ++k) {
    TrialParams& t = trials[k];
    const double g = lower_bound(t.m, t.kappa);
    if (k % 3 != 1) t.kd = 2 * u(rng) * g;
    if (k % 3 != 2) t.rayleigh_mass = 2 * u(rng) * g / t.m;
    if (k % 4 != 0) t.rayleigh_stiffness = 0.02 * u(rng);
    if (k % 9 == 0) t.kd = t.rayleigh_mass = t.rayleigh_stiffness = 0.0;  // undamped in the mix
  }
  for (StopRule rule : {StopRule::first_entry, StopRule::settled}) {
    FlatSeen seen{};
    for (DampingPolicy p : kPolicies) {
      StopRules rules;
      rules.rule = rule;
      rules.reference = 0.6;
      rules.max_iterations = 150;
      add(seen, expect_body_matches(irregular, p, rules, trials, stepped));
      rules = plane.rules;
      rules.rule = rule;
      rules.max_iterations = 100;
      add(seen, expect_body_matches(plane, p, rules, trials, stepped));
    }
    expect_every_verdict(seen, rule);
  }
}

TEST(TrialBody, RefusesCutsAndOtherIntegrators) {
  SceneSpec s = paper_plane_scene(4);
  EXPECT_FALSE(trial_body_unsupported(s));
  s.params.integrator = Integrator::rk4;
  EXPECT_TRUE(trial_body_unsupported(s));
  EXPECT_THROW(FlatScene(s, DampingPolicy::fixed, s.rules), std::invalid_argument);
  s.params.integrator = Integrator::forward_euler;
  EXPECT_FALSE(trial_body_unsupported(s));
  s.params.kd = 0.001;  // SPEC 10 damping is the body's own
  EXPECT_FALSE(trial_body_unsupported(s));
}

}  // namespace
}  // namespace dampbound
