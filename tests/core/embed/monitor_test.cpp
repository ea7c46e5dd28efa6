// The monitor over a user's arrays against core's own step() on the same model: equal bounds,
// effective damping and counts, bit for bit; the exact limits against SPEC 7's closed form;
// bad topology named.
#include "dampbound/monitor.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>
#include <stdexcept>

#include "dampbound/run/session.hpp"

namespace dampbound {
namespace {

/// The scene's model as plain arrays, the way a user's simulator holds them.
struct UserArrays {
  std::vector<double> mass, gamma, stiffness, rest_length, anchor;
  std::vector<int> pairs;
  std::vector<std::array<double, 3>> rest;
  explicit UserArrays(const Model& mo) {
    for (int i = 0; i < mo.spec().node_count(); ++i) {
      const size_t k = static_cast<size_t>(i);
      mass.push_back(mo.mass[k]);
      gamma.push_back(mo.gamma[k]);
      anchor.push_back(mo.anchor_kappa[k]);
      rest.push_back({mo.spec().rest[k].x(), mo.spec().rest[k].y(), mo.spec().rest[k].z()});
    }
    for (size_t k = 0; k < mo.spec().springs.size(); ++k) {
      const Spring& s = mo.spec().springs[k];
      pairs.insert(pairs.end(), {s.i, s.j});
      stiffness.push_back(mo.spring_kappa[k]);
      rest_length.push_back(s.rest_length);
    }
  }
  Monitor monitor() const {
    const auto n = static_cast<Eigen::Index>(mass.size());
    const auto s = static_cast<Eigen::Index>(stiffness.size());
    Monitor mon(node_scalars(mass.data(), n), spring_pairs(pairs.data(), s),
                node_scalars(stiffness.data(), s), node_scalars(rest_length.data(), s));
    mon.set_anchors(node_scalars(anchor.data(), n), node_vectors(rest[0].data(), n));
    return mon;
  }
};

TEST(Monitor, MatchesStepBitForBitUnderClamp) {
  SceneSpec scene = paper_plane_scene(7);
  Params p = scene.params;
  p.policy = DampingPolicy::clamp;
  p.gamma = 0.0004;
  Session session(scene, p, scene.rules);
  const UserArrays user(session.model());
  const Monitor mon = user.monitor();
  const Eigen::Index n = mon.node_count();
  std::vector<double> lo(static_cast<size_t>(n)), hi(lo.size()), g(lo.size());
  mon.lower_bounds(node_scalars_out(lo.data(), n));
  EXPECT_EQ(lo, session.model().lower_bound);
  for (int it = 0; it < 6; ++it) {
    const State before = session.state();
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> f(n, 3);
    mon.internal_forces(node_vectors(before.x[0].data(), n), f);
    auto g_out = node_scalars_out(g.data(), n);
    auto hi_out = node_scalars_out(hi.data(), n);
    const MonitorReport r =
        mon.check(node_vectors(before.v[0].data(), n), node_vectors(f.data(), n),
                  node_scalars(user.gamma.data(), n), p.dt, p.policy, p.factor, &g_out, &hi_out);
    const StepStats st = session.step_once();
    EXPECT_EQ(hi, session.workspace().upper_bound) << "step " << it;
    EXPECT_EQ(g, session.workspace().gamma_eff) << "step " << it;
    EXPECT_EQ(r.violating, st.violating);
    EXPECT_EQ(r.unstabilisable, st.unstabilisable);
    EXPECT_EQ(r.clamped, st.clamped);
  }
}

// SPEC 9 through the monitor: the safe bounds and the safe policy's damping equal step()'s,
// bit for bit, on a run whose absurd damping the policy must cut down.
TEST(Monitor, MatchesStepBitForBitUnderSafe) {
  SceneSpec scene = paper_plane_scene(7);
  Params p = scene.params;
  p.policy = DampingPolicy::safe;
  p.gamma = 1.0;
  Session session(scene, p, scene.rules);
  const UserArrays user(session.model());
  const Monitor mon = user.monitor();
  const Eigen::Index n = mon.node_count();
  std::vector<double> safe(static_cast<size_t>(n)), g(safe.size());
  int clamped_steps = 0;
  for (int it = 0; it < 6; ++it) {
    const State before = session.state();
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> f(n, 3);
    mon.internal_forces(node_vectors(before.x[0].data(), n), f);
    mon.safe_bounds(node_vectors(before.x[0].data(), n), p.dt, node_scalars_out(safe.data(), n));
    auto g_out = node_scalars_out(g.data(), n);
    const MonitorReport r = mon.check(
        node_vectors(before.x[0].data(), n), node_vectors(before.v[0].data(), n),
        node_vectors(f.data(), n), node_scalars(user.gamma.data(), n), p.dt, p.policy, p.factor,
        &g_out);
    const StepStats st = session.step_once();
    EXPECT_EQ(safe, session.workspace().safe_bound) << "step " << it;
    EXPECT_EQ(g, session.workspace().gamma_eff) << "step " << it;
    EXPECT_EQ(r.unguaranteed, st.unguaranteed);
    EXPECT_EQ(r.compressed_springs, st.compressed_springs);
    EXPECT_EQ(r.clamped, st.clamped);
    clamped_steps += r.clamped > 0;
  }
  EXPECT_EQ(clamped_steps, 6);  // gamma = 1 is far above gamma_safe ~ 0.04: every step clamps
  for (double v : g) EXPECT_LT(v, 0.05);
  // Without positions the safe policy cannot be evaluated: refused, not guessed.
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> zero =
      Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>::Zero(n, 3);
  EXPECT_THROW(mon.check(node_vectors(zero.data(), n), node_vectors(zero.data(), n),
                         node_scalars(user.gamma.data(), n), p.dt, DampingPolicy::safe),
               std::invalid_argument);
}

TEST(Monitor, ThreadsGiveTheSameBitsAndTheSameFirstIndices) {
  // A 52 900-node plane (157 781 springs: both loops split into 3 ranges on 3 threads) in a
  // random state with some fixed nodes. Nodes below 45 % stand still (their upper bound is
  // +inf), so the first range finds no violating node and the second and third do: the
  // report must skip the first and take the second's.
  SceneSpec scene = paper_plane_scene(230);
  for (size_t i = 0; i < scene.model.fixed.size(); i += 97) scene.model.fixed[i] = 1;
  const Session session(scene, scene.params, scene.rules);
  const UserArrays user(session.model());
  Monitor one = user.monitor();
  std::vector<std::uint8_t> fixed(session.model().spec().fixed.begin(), session.model().spec().fixed.end());
  const Eigen::Index n = one.node_count();
  one.set_fixed(fixed.data(), n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> x(3 * static_cast<size_t>(n)), v(x.size()), gamma(static_cast<size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    const size_t k = static_cast<size_t>(i);
    for (int c = 0; c < 3; ++c) {
      x[3 * k + static_cast<size_t>(c)] = session.model().spec().rest[k][c] + 0.2 * u(rng);
      v[3 * k + static_cast<size_t>(c)] = i < 45 * n / 100 ? 0.0 : 5 * u(rng);
    }
    gamma[k] = 3 * session.model().mass[k] / scene.params.dt;  // above eq. 6's m/dt + |F|/|v|
  }
  struct Out {
    std::vector<double> force, safe, g, hi, upper;
    std::vector<NodeStatus> status;
    MonitorReport report;
    int zero_length = 0, compressed = 0;
  };
  auto evaluate = [&](const Monitor& mon) {
    Out o;
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> f(n, 3);
    o.zero_length = mon.internal_forces(node_vectors(x.data(), n), f);
    o.force.assign(f.data(), f.data() + 3 * n);
    o.safe.resize(static_cast<size_t>(n));
    o.compressed = mon.safe_bounds(node_vectors(x.data(), n), scene.params.dt,
                                   node_scalars_out(o.safe.data(), n));
    o.g.resize(static_cast<size_t>(n));
    o.hi.resize(static_cast<size_t>(n));
    o.status.resize(static_cast<size_t>(n));
    auto g_out = node_scalars_out(o.g.data(), n);
    auto hi_out = node_scalars_out(o.hi.data(), n);
    o.report = mon.check(node_vectors(x.data(), n), node_vectors(v.data(), n),
                         node_vectors(f.data(), n), node_scalars(gamma.data(), n),
                         scene.params.dt, DampingPolicy::fixed, 1.0, &g_out, &hi_out,
                         o.status.data());
    o.upper.resize(static_cast<size_t>(n));
    mon.upper_bounds(node_vectors(v.data(), n), node_vectors(f.data(), n), scene.params.dt,
                     node_scalars_out(o.upper.data(), n));
    return o;
  };
  const Out a = evaluate(one);
  ASSERT_GT(a.report.violating, 0);
  ASSERT_GT(a.compressed, 0);
  int first = -1;
  for (Eigen::Index i = 0; i < n && first < 0; ++i)
    if (a.status[static_cast<size_t>(i)] == NodeStatus::violating) first = static_cast<int>(i);
  EXPECT_EQ(a.report.first_violating, first);
  EXPECT_GT(first, n / 3);
  EXPECT_LT(first, 2 * n / 3);
  for (int threads : {2, 3}) {
    SCOPED_TRACE(threads);
    Monitor many = one;
    many.set_threads(threads);
    EXPECT_EQ(many.threads(), threads);
    const Out b = evaluate(many);
    EXPECT_EQ(b.force, a.force);
    EXPECT_EQ(b.safe, a.safe);
    EXPECT_EQ(b.g, a.g);
    EXPECT_EQ(b.hi, a.hi);
    EXPECT_EQ(b.upper, a.upper);
    EXPECT_EQ(b.status, a.status);
    EXPECT_EQ(b.zero_length, a.zero_length);
    EXPECT_EQ(b.compressed, a.compressed);
    EXPECT_EQ(b.report.violating, a.report.violating);
    EXPECT_EQ(b.report.unstabilisable, a.report.unstabilisable);
    EXPECT_EQ(b.report.clamped, a.report.clamped);
    EXPECT_EQ(b.report.unguaranteed, a.report.unguaranteed);
    EXPECT_EQ(b.report.first_violating, a.report.first_violating);
    EXPECT_EQ(b.report.first_unstabilisable, a.report.first_unstabilisable);
  }
}

TEST(Monitor, UpperBoundIsEq6AndInfiniteAtRest) {
  const double mass[] = {2.0, 3.0}, k[] = {5.0}, l0[] = {1.0};
  const int pairs[] = {0, 1};
  const Monitor mon(node_scalars(mass, 2), spring_pairs(pairs, 1), node_scalars(k, 1),
                    node_scalars(l0, 1));
  const double v[] = {0, 0, 0, 1, 2, 0}, f[] = {0, 0, 0, -4, 0, 0};
  double hi[2];
  mon.upper_bounds(node_vectors(v, 2), node_vectors(f, 2), 0.5, node_scalars_out(hi, 2));
  EXPECT_TRUE(std::isinf(hi[0]));
  // |v m/dt + F| / |v| = |(6 - 4, 12, 0)| / sqrt(5)
  EXPECT_DOUBLE_EQ(hi[1], std::sqrt(4.0 + 144.0) / std::sqrt(5.0));
}

TEST(Monitor, ExactLimitsOfTwoFreeNodesAreSpec7s) {
  const double mass[] = {0.5, 0.5}, k[] = {2.0}, l0[] = {1.0}, gamma[] = {0.1, 0.1};
  const double x[] = {0, 0, 0, 1, 0, 0};
  const int pairs[] = {0, 1};
  const Monitor mon(node_scalars(mass, 2), spring_pairs(pairs, 1), node_scalars(k, 1),
                    node_scalars(l0, 1));
  const double dt = 0.1, lambda = 2 * 2.0 / 0.5;  // the stretching mode: 2 kappa/m
  const MonitorLimits l = mon.exact_limits(node_vectors(x, 2), node_scalars(gamma, 2), dt);
  EXPECT_NEAR(l.lambda_max, lambda, 1e-9 * lambda);
  EXPECT_NEAR(l.rate_max, 2 / dt - lambda * dt / 2, 1e-9);
  EXPECT_NEAR(l.dt_max_undamped, 2 / std::sqrt(lambda), 1e-9);
  EXPECT_TRUE(l.stable);
  // gamma_i scaled by s is stable below m (2/dt - lambda dt/2) / gamma_i.
  EXPECT_NEAR(l.scale_hi, 0.5 * (2 / dt - lambda * dt / 2) / 0.1, 1e-6);
}

TEST(Monitor, ExactLimitsOverAFactorisationBudgetFactoriseNothing) {
  // A 12 x 12 grid with right and down springs: 432 rows, the factorisation route.
  const int n = 12, nodes = n * n;
  std::vector<double> mass(nodes, 0.001), x(3 * nodes), gamma(nodes, 0.002), k, l0;
  std::vector<int> pairs;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const int i = a * n + b;
      x[3 * i] = 0.57 * a;
      x[3 * i + 2] = 0.57 * b;
      for (int j : {b + 1 < n ? i + 1 : -1, a + 1 < n ? i + n : -1})
        if (j >= 0) pairs.push_back(i), pairs.push_back(j), k.push_back(0.001), l0.push_back(0.57);
    }
  const int springs = static_cast<int>(k.size());
  const std::vector<double> anchors(nodes, 0.001);
  Monitor mon(node_scalars(mass.data(), nodes), spring_pairs(pairs.data(), springs),
              node_scalars(k.data(), springs), node_scalars(l0.data(), springs));
  mon.set_anchors(node_scalars(anchors.data(), nodes), node_vectors(x.data(), nodes));
  const MonitorLimits free = mon.exact_limits(node_vectors(x.data(), nodes), node_scalars(gamma.data(), nodes), 0.05);
  EXPECT_FALSE(free.not_computed.has_value());
  EXPECT_GT(free.lambda_max, 0);
  const MonitorLimits over =
      mon.exact_limits(node_vectors(x.data(), nodes), node_scalars(gamma.data(), nodes), 0.05, 1.0);
  ASSERT_TRUE(over.not_computed.has_value());
  EXPECT_NE(over.not_computed->find("over the budget"), std::string::npos) << *over.not_computed;
  for (double v : {over.lambda_max, over.scale_lo, over.scale_hi, over.dt_max, over.rate_max,
                   over.dt_max_undamped})
    EXPECT_TRUE(std::isnan(v));
  // Not computed, but proved stable: Gershgorin on the index matrix, SPEC 9's safe bound (no
  // spring compressed), inside the exact limits.
  EXPECT_TRUE(over.stable);
  EXPECT_TRUE(std::isnan(free.dt_stable_up_to));
  EXPECT_GE(over.scale_stable_up_to, 1.0);  // the given gamma_i, s = 1
  EXPECT_LE(over.scale_stable_up_to, free.scale_hi);
  EXPECT_GE(over.dt_stable_up_to, 0.05);
  EXPECT_LE(over.dt_stable_up_to, free.dt_max);
  EXPECT_TRUE(std::isnan(free.dt_unstable_from));
  // What Lanczos proves without a factorisation lies on the unstable side of the exact limits.
  EXPECT_LE(over.lambda_max_at_least, free.lambda_max);
  EXPECT_GE(over.scale_unstable_from, free.scale_hi);
  EXPECT_LT(over.scale_unstable_from, free.scale_hi * (1 + 1e-3));
  EXPECT_GE(over.dt_unstable_from, free.dt_max);
  EXPECT_LT(over.dt_unstable_from, free.dt_max * (1 + 1e-3));
  const MonitorLimits roomy =
      mon.exact_limits(node_vectors(x.data(), nodes), node_scalars(gamma.data(), nodes), 0.05, 1e12);
  EXPECT_EQ(roomy.lambda_max, free.lambda_max);
  EXPECT_EQ(roomy.dt_max, free.dt_max);
  EXPECT_THROW(mon.exact_limits(node_vectors(x.data(), nodes), node_scalars(gamma.data(), nodes), 0.05, 0.0),
               std::invalid_argument);
}

TEST(Monitor, BadTopologyIsNamed) {
  const double mass[] = {1.0, 1.0}, k[] = {1.0}, bad_k[] = {-1.0}, l0[] = {1.0};
  const int out_of_range[] = {0, 2}, self[] = {1, 1}, ok[] = {0, 1};
  auto make = [&](const int* pairs, const double* kk) {
    return Monitor(node_scalars(mass, 2), spring_pairs(pairs, 1), node_scalars(kk, 1),
                   node_scalars(l0, 1));
  };
  EXPECT_THROW(make(out_of_range, k), std::invalid_argument);
  EXPECT_THROW(make(self, k), std::invalid_argument);
  try {
    make(ok, bad_k);
    FAIL() << "negative stiffness accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("spring 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dampbound
