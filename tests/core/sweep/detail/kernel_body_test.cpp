// The batched kernel against the one step() of core: the same trials through
// BatchKernel and through Session::run_to_end must give the same outcome, iteration, counts
// and (bit for bit) the same final maximum displacement.
#include "core/sweep/kernel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/io/scene_file.hpp"
#include "core/sweep/trials.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

SceneSpec shipped(const std::string& name) {
  return load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/" + name + ".toml");
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

std::string describe(const TrialParams& t, DampingPolicy p) {
  return "m=" + std::to_string(t.m) + " kappa=" + std::to_string(t.kappa) +
         " gamma=" + std::to_string(t.gamma) + " dt=" + std::to_string(t.dt) +
         " policy=" + to_string(p) + " factor=" + std::to_string(t.factor);
}

constexpr size_t kOutcomes = 6;  // Outcome's values
constexpr size_t kLeft = kOutcomes;  // the extra slot of Seen: trials that entered and left
using Seen = std::array<int, kOutcomes + 1>;

/// The kernel copies this CPU runs (generic, and avx2, avx512 where it has them), named in
/// the test's output.
std::vector<KernelIsa> copies_here() {
  std::vector<KernelIsa> copies;
  std::string names;
  for (KernelIsa isa : {KernelIsa::generic, KernelIsa::avx2, KernelIsa::avx512})
    if (kernel_isa_supported(isa)) {
      copies.push_back(isa);
      names += std::string(names.empty() ? "" : " ") + to_string(isa);
    }
  // Once per test.
  if (::testing::UnitTest::GetInstance()->current_test_info()->result()->test_property_count() == 0)
    test::say_kernel_copies(names);
  return copies;
}

/// Runs every trial through step() and through every kernel copy this CPU runs, and
/// compares; returns how many ended in each outcome (and how many entered the band and left
/// it) so the caller can check the sample really covers every verdict.
Seen expect_same(const SceneSpec& scene, DampingPolicy policy, const StopRules& rules,
                               const std::vector<TrialParams>& trials) {
  Seen seen{};
  std::vector<TrialResult> refs;
  for (const TrialParams& t : trials) {
    refs.push_back(run_reference(scene, policy, rules, t));
    ++seen[static_cast<size_t>(refs.back().outcome)];
    seen[kLeft] += refs.back().left_at > 0;
  }
  for (KernelIsa isa : copies_here()) {
    const std::vector<TrialResult> batched = run_batched(scene, policy, rules, trials, isa);
    for (size_t k = 0; k < trials.size(); ++k) {
      const TrialResult& ref = refs[k];
      const TrialResult& got = batched[k];
      SCOPED_TRACE(std::string(to_string(isa)) + " " + describe(trials[k], policy));
      EXPECT_EQ(to_string(got.outcome), std::string(to_string(ref.outcome)));
      EXPECT_EQ(got.iterations, ref.iterations);
      EXPECT_TRUE(same_bits(got.max_displacement, ref.max_displacement))
          << got.max_displacement << " vs " << ref.max_displacement;
      EXPECT_EQ(got.violations, ref.violations);
      EXPECT_EQ(got.unstabilisable, ref.unstabilisable);
      EXPECT_EQ(got.clamped, ref.clamped);
      EXPECT_EQ(got.zero_length_springs, ref.zero_length_springs);
      EXPECT_EQ(got.first_entry, ref.first_entry);
      EXPECT_EQ(got.left_at, ref.left_at);
      EXPECT_EQ(got.settled_at, ref.settled_at);
    }
  }
  return seen;
}

TEST(SweepKernel, TwoNodeSceneEveryPolicyMatchesStep) {
  // General topology: a fixed node, one spring, no anchors.
  const SceneSpec scene = shipped("two-node");
  StopRules rules = scene.rules;
  rules.reference = 0.5;
  rules.max_iterations = 400;
  std::vector<TrialParams> trials;
  for (double m : {0.0005, 0.001, 0.004})
    for (double kappa : {0.001, 0.01, 0.3, 1.7})
      for (double zeta : {0.0, 0.3, 1.0, 3.0}) {
        TrialParams t;
        t.m = m;
        t.kappa = kappa;
        t.gamma = zeta * lower_bound(m, kappa);
        t.factor = zeta > 1 ? 1.05 : 1.0;
        trials.push_back(t);
      }
  for (StopRule rule : {StopRule::first_entry, StopRule::settled}) {
    rules.rule = rule;
    Seen seen{};
    for (DampingPolicy p :
         {DampingPolicy::fixed, DampingPolicy::clamp, DampingPolicy::upper, DampingPolicy::lower,
           DampingPolicy::safe}) {
      const auto s = expect_same(scene, p, rules, trials);
      for (size_t k = 0; k < seen.size(); ++k) seen[k] += s[k];
    }
    const bool settled = rule == StopRule::settled;
    EXPECT_GT(seen[static_cast<size_t>(settled ? Outcome::settled : Outcome::restored)], 0);
    EXPECT_GT(seen[static_cast<size_t>(Outcome::diverged)], 0);
    EXPECT_GT(seen[static_cast<size_t>(settled ? Outcome::not_settled : Outcome::not_restored)], 0);
    // The undamped oscillator passes through the band and out again: the settled rule's case.
    if (settled) {
      EXPECT_GT(seen[kLeft], 0);
    }
  }
}

/// An irregular scene built in code: non-uniform mass, gamma and stiffness scales, partial
/// anchors, an external force, a fixed node and a spring of zero rest length between two
/// nodes that start at the same place (zero current length: skipped and counted).
SceneSpec irregular_scene() {
  SceneSpec s;
  s.name = "irregular";
  ModelSpec& m = s.model;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 23; ++i) add_node(m, Vec3(u(rng) * 3, u(rng) * 0.5, u(rng) * 3));
  add_node(m, m.rest[5]);  // node 23 sits on node 5
  for (int i = 0; i < 24; ++i) {
    m.mass_scale[static_cast<size_t>(i)] = 0.5 + u(rng);
    m.gamma_scale[static_cast<size_t>(i)] = 0.5 + u(rng);
    if (i % 3 != 0) m.anchor_scale[static_cast<size_t>(i)] = 0.2 + u(rng);
  }
  m.fixed[0] = 1;
  m.external_force[7] = Vec3(0, -0.0004, 0.0001);
  for (int i = 0; i < 23; ++i)
    for (int j = i + 1; j < 23; ++j)
      if (u(rng) < 0.18) add_spring(m, i, j, 0.3 + 2 * u(rng));
  add_spring(m, 5, 23, 1.0);
  add_spring(m, 23, 9, 1.0);
  s.params = default_params();
  s.perturbations.push_back({12, Vec3(0.2, 0.6, -0.1), Vec3::Zero()});
  s.perturbations.push_back({3, Vec3::Zero(), Vec3(0.1, 0.0, 0.3)});
  s.watched = 12;
  return s;
}

TEST(SweepKernel, IrregularSceneMatchesStep) {
  const SceneSpec scene = irregular_scene();
  StopRules rules;
  rules.reference = 0.6;
  rules.max_iterations = 300;
  std::vector<TrialParams> trials;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 40; ++k) {
    TrialParams t;
    t.m = 0.0005 + 0.01 * u(rng);
    t.kappa = 0.0005 + 0.2 * u(rng);
    t.gamma = 2.5 * u(rng) * lower_bound(t.m, t.kappa);
    t.dt = k % 2 ? 0.05 : 0.02;
    t.factor = k % 3 ? 1.0 : 1.05;
    trials.push_back(t);
  }
  long long zero_length = 0;
  for (StopRule rule : {StopRule::first_entry, StopRule::settled})
    for (DampingPolicy p :
         {DampingPolicy::fixed, DampingPolicy::clamp, DampingPolicy::upper, DampingPolicy::lower,
           DampingPolicy::safe}) {
      rules.rule = rule;
      expect_same(scene, p, rules, trials);
      zero_length += run_batched(scene, p, rules, {trials[0]})[0].zero_length_springs;
    }
  EXPECT_GT(zero_length, 0) << "the coincident nodes should give zero-length springs";
}

TEST(SweepKernel, ForwardEulerMatchesStep) {
  SceneSpec scene = irregular_scene();
  scene.params.integrator = Integrator::forward_euler;
  StopRules rules;
  rules.reference = 0.6;
  rules.max_iterations = 200;
  std::vector<TrialParams> trials;
  for (double zeta : {0.5, 1.0, 2.0, 6.0}) {
    TrialParams t;
    t.m = 0.002;
    t.kappa = 0.01;
    t.gamma = zeta * lower_bound(t.m, t.kappa);
    trials.push_back(t);
  }
  expect_same(scene, DampingPolicy::fixed, rules, trials);
  rules.rule = StopRule::settled;
  expect_same(scene, DampingPolicy::fixed, rules, trials);
}

/// The paper's mesh with borderline trials: gamma around the value where the run restores
/// exactly at the iteration limit, kappa/m around the edge of divergence, each policy.
TEST(SweepKernel, PaperPlaneBorderlineTrialsMatchStep) {
  const SceneSpec scene = shipped("paper-plane");
  StopRules rules = scene.rules;
  rules.rule = StopRule::first_entry;  // the outcomes counted below are the paper's
  rules.max_iterations = 60;
  std::vector<TrialParams> fixed_trials;
  // Near the restore threshold at the limit: zeta swept finely where runs restore in ~60.
  for (int k = 0; k <= 12; ++k) {
    TrialParams t;
    t.m = 0.001;
    t.kappa = 0.01;
    t.gamma = (0.30 + 0.01 * k) * lower_bound(t.m, t.kappa);
    fixed_trials.push_back(t);
  }
  // Near divergence: kappa/m across the range where the mesh starts to blow up.
  for (double r : {100.0, 140.0, 160.0, 170.0, 175.0, 180.0, 190.0, 220.0, 400.0}) {
    TrialParams t;
    t.m = 0.0005;
    t.kappa = r * t.m;
    t.gamma = 0.25 * lower_bound(t.m, t.kappa);
    fixed_trials.push_back(t);
  }
  const auto seen = expect_same(scene, DampingPolicy::fixed, rules, fixed_trials);
  EXPECT_GT(seen[static_cast<size_t>(Outcome::restored)], 0);
  EXPECT_GT(seen[static_cast<size_t>(Outcome::not_restored)], 0);
  EXPECT_GT(seen[static_cast<size_t>(Outcome::diverged)], 0);
  StopRules settled = rules;
  settled.rule = StopRule::settled;
  const auto seen_settled = expect_same(scene, DampingPolicy::fixed, settled, fixed_trials);
  EXPECT_GT(seen_settled[static_cast<size_t>(Outcome::settled)], 0);
  EXPECT_GT(seen_settled[static_cast<size_t>(Outcome::not_settled)], 0);
  EXPECT_GT(seen_settled[static_cast<size_t>(Outcome::diverged)], 0);

  std::vector<TrialParams> few;
  for (double r : {0.5, 20.0, 160.0}) {
    for (double factor : {1.0, 1.05}) {
      TrialParams t;
      t.m = 0.005;
      t.kappa = r * t.m;
      t.gamma = 0.7 * lower_bound(t.m, t.kappa);
      t.factor = factor;
      few.push_back(t);
    }
  }
  for (DampingPolicy p : {DampingPolicy::clamp, DampingPolicy::upper, DampingPolicy::lower,
                          DampingPolicy::safe}) {
    expect_same(scene, p, rules, few);
    expect_same(scene, p, settled, few);
  }
}

/// The safe policy (SPEC 9) through every branch: the user's gamma above gamma_safe (clamped
/// down), inside [gamma_lo, gamma_safe], below gamma_lo (clamped up), and an empty interval
/// (gamma_lo > gamma_safe, also with gamma_safe < 0), on the paper plane (uniform scales)
/// and the irregular scene (per-node masses, a fixed node, a zero-length spring).
TEST(SweepKernel, SafePolicyMatchesStepInEveryBranch) {
  std::vector<TrialParams> trials;
  for (double r : {1.0, 20.0, 160.0, 400.0, 2000.0})
    for (double gamma_over_m : {0.0, 1.0, 30.0, 1e4}) {
      TrialParams t;
      t.m = 0.002;
      t.kappa = r * t.m;
      t.gamma = gamma_over_m * t.m;
      trials.push_back(t);
    }
  StopRules rules;
  rules.max_iterations = 80;
  long long clamped = 0;
  for (const SceneSpec& scene : {shipped("paper-plane"), irregular_scene()}) {
    rules.reference = scene.name == "irregular" ? 0.6 : 5.0;
    expect_same(scene, DampingPolicy::safe, rules, trials);
    for (const TrialResult& r : run_batched(scene, DampingPolicy::safe, rules, trials))
      clamped += r.clamped;
  }
  EXPECT_GT(clamped, 0);
}

TEST(SweepKernel, SpringScheduleKeepsEachNodesOrder) {
  const SceneSpec scene = shipped("paper-plane");
  const ModelSpec& m = scene.model;
  const std::vector<int> order = spring_schedule(m);
  ASSERT_EQ(order.size(), m.springs.size());
  std::vector<int> seen(m.springs.size(), 0);
  for (int k : order) ++seen[static_cast<size_t>(k)];
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(seen.size()));
  // For every node, its springs appear in increasing list order.
  std::vector<int> last(m.rest.size(), -1);
  int neighbours_sharing = 0;
  for (size_t p = 0; p < order.size(); ++p) {
    const Spring& s = m.springs[static_cast<size_t>(order[p])];
    for (int node : {s.i, s.j}) {
      EXPECT_LT(last[static_cast<size_t>(node)], order[p]);
      last[static_cast<size_t>(node)] = order[p];
    }
    if (p > 0) {
      const Spring& q = m.springs[static_cast<size_t>(order[p - 1])];
      neighbours_sharing += s.i == q.i || s.i == q.j || s.j == q.i || s.j == q.j;
    }
  }
  // The list order shares a node between most neighbours; the schedule rarely does.
  int list_sharing = 0;
  for (size_t p = 1; p < m.springs.size(); ++p) {
    const Spring& s = m.springs[p];
    const Spring& q = m.springs[p - 1];
    list_sharing += s.i == q.i || s.i == q.j || s.j == q.i || s.j == q.j;
  }
  EXPECT_GT(list_sharing, static_cast<int>(order.size() / 2));
  EXPECT_LT(neighbours_sharing, list_sharing / 20);
}

}  // namespace
}  // namespace dampbound
