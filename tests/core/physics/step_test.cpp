// The paper's step (SPEC 2) against the closed-form solution of its own recurrence.
#include "dampbound/physics/step.hpp"

#include <gtest/gtest.h>

#include <complex>
#include <cstring>

#include "core/io/scene_file.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/run/session.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

// For one anchored node (lambda = kappa/m, c = gamma/m) the step gives
// x_{n+1} = (2 - c dt - lambda dt^2) x_n - (1 - c dt) x_{n-1}, x_1 = x_0 (1 - lambda dt^2),
// so x_n = A z1^n + B z2^n with z1, z2 the roots of z^2 - (2 - c dt - lambda dt^2) z + 1 - c dt.
double closed_form(double x0, double lambda, double c, double dt, int n) {
  using C = std::complex<double>;
  const double b = 2 - c * dt - lambda * dt * dt, q = 1 - c * dt;
  const C disc = std::sqrt(C(b * b - 4 * q));
  const C z1 = (b + disc) / 2.0, z2 = (b - disc) / 2.0;
  const double x1 = x0 * (1 - lambda * dt * dt);
  const C B = (x1 - x0 * z1) / (z2 - z1), A = x0 - B;
  return (A * std::pow(z1, n) + B * std::pow(z2, n)).real();
}

struct OscCase {
  double m, kappa, gamma, dt;
};

class StepClosedForm : public ::testing::TestWithParam<OscCase> {};

TEST_P(StepClosedForm, MatchesRecurrence) {
  const OscCase k = GetParam();
  Params p;
  p.m = k.m, p.kappa = k.kappa, p.gamma = k.gamma, p.dt = k.dt;
  Model model = test::single_oscillator(p);
  State s = rest_state(model);
  const double x0 = 0.7;
  s.x[0].y() = x0;
  StepWorkspace ws;
  for (int n = 1; n <= 300; ++n) {
    step(model, p, s, ws);
    const double expected = closed_form(x0, k.kappa / k.m, k.gamma / k.m, k.dt, n);
    ASSERT_NEAR(s.x[0].y(), expected, 1e-9 * (1 + std::abs(expected))) << "n=" << n;
    ASSERT_EQ(s.x[0].x(), 0.0);
  }
}

std::string case_name(const ::testing::TestParamInfo<OscCase>& param) {
  static const char* const names[] = {"undamped", "underdamped", "critical", "overdamped", "stiff"};
  return names[param.index];
}

INSTANTIATE_TEST_SUITE_P(Oscillators, StepClosedForm,
                         ::testing::Values(OscCase{0.001, 0.001, 0.0, 0.05},     // undamped
                                           OscCase{0.001, 0.001, 0.0005, 0.05},  // under
                                           OscCase{0.001, 0.001, 0.002, 0.05},   // critical
                                           OscCase{0.001, 0.001, 0.01, 0.05},    // over
                                           OscCase{0.005, 0.1, 0.01, 0.05}),
                         case_name);

TEST(Step, UsesNewVelocityForPosition) {
  // One step by hand: a = (F - gamma v)/m, v1 = v0 + a dt, x1 = x0 + v1 dt (eqs. 3-4).
  Params p;
  p.m = 2, p.kappa = 3, p.gamma = 0.5, p.dt = 0.1;
  Model model = test::single_oscillator(p);
  State s = rest_state(model);
  s.x[0] = Vec3(1, 0, 0);
  s.v[0] = Vec3(0.4, 0, 0);
  StepWorkspace ws;
  const StepStats st = step(model, p, s, ws);
  const double a = (-3 * 1.0 - 0.5 * 0.4) / 2;
  const double v1 = 0.4 + a * 0.1, x1 = 1 + v1 * 0.1;
  EXPECT_DOUBLE_EQ(s.v[0].x(), v1);
  EXPECT_DOUBLE_EQ(s.x[0].x(), x1);
  EXPECT_EQ(st.iteration, 1);
  EXPECT_DOUBLE_EQ(st.time, 0.1);
  const NodeSample w = sample_node(model, s, ws, 0);
  EXPECT_DOUBLE_EQ(w.displacement, std::abs(x1));
  EXPECT_DOUBLE_EQ(w.gamma_eff, 0.5);
  EXPECT_DOUBLE_EQ(w.lower, 2 * std::sqrt(2.0 * 3.0));
}

TEST(Step, FixedNodeNeverMoves) {
  SceneSpec scene = load_scene(test::source_path("scenes/two-node.toml"));
  Session session(scene);
  for (int k = 0; k < 50; ++k) session.step_once();
  EXPECT_EQ(session.state().x[0], Vec3::Zero());
  EXPECT_EQ(session.workspace().status[0], NodeStatus::fixed);
  EXPECT_NE(session.state().x[1], scene.model.rest[1]);
}

TEST(Step, ExternalForceAccelerates) {
  Params p;
  p.m = 2, p.gamma = 0, p.dt = 0.5;
  ModelSpec spec;
  add_node(spec, Vec3::Zero());
  spec.external_force[0] = Vec3(0, -4, 0);
  const Model model = compile_model(std::move(spec), p);
  State s = rest_state(model);
  StepWorkspace ws;
  step(model, p, s, ws);
  EXPECT_DOUBLE_EQ(s.v[0].y(), -1.0);  // a = -2, v = -1
  EXPECT_DOUBLE_EQ(s.x[0].y(), -0.5);  // x = v_new dt
}

TEST(Step, ZeroLengthSpringIsCountedNotNaN) {
  Params p;
  ModelSpec spec;
  add_node(spec, Vec3::Zero());
  add_node(spec, Vec3(1, 0, 0));
  add_spring(spec, 0, 1);
  const Model model = compile_model(std::move(spec), p);
  State s = rest_state(model);
  s.x[1] = s.x[0];  // both nodes on the same point: no direction
  StepWorkspace ws;
  const StepStats st = step(model, p, s, ws);
  EXPECT_EQ(st.zero_length_springs, 1);
  EXPECT_TRUE(st.finite);
  EXPECT_TRUE(s.x[1].allFinite());
}

TEST(Step, DeterministicTraces) {
  SceneSpec scene = load_scene(test::source_path("scenes/paper-plane.toml"));
  Params p = scene.params;
  p.gamma = 0.0007;
  p.policy = DampingPolicy::clamp;
  Session a(scene, p, scene.rules), b(scene, p, scene.rules);
  a.run_to_end();
  b.run_to_end();
  ASSERT_EQ(a.trace().size(), b.trace().size());
  for (size_t k = 0; k < a.trace().size(); ++k) {
    const StepSample &x = a.trace()[k], &y = b.trace()[k];
    ASSERT_EQ(std::memcmp(&x.watched.displacement, &y.watched.displacement, sizeof(double)), 0);
    ASSERT_EQ(std::memcmp(&x.watched.upper, &y.watched.upper, sizeof(double)), 0);
    ASSERT_EQ(std::memcmp(&x.max_displacement, &y.max_displacement, sizeof(double)), 0);
    ASSERT_EQ(x.violating, y.violating);
  }
  for (size_t i = 0; i < a.state().x.size(); ++i) ASSERT_EQ(a.state().x[i], b.state().x[i]);
}

/// A perturbed 3D lattice big enough to split (9261 nodes, ~60k springs): varied scales, some
/// fixed nodes, an external force, stretched and compressed springs.
Model lattice(const Params& p) {
  return compile_model(test::cube_lattice(21, 0.5,
                                          [](ModelSpec& m, int i, int a, int b, int) {
                                            m.mass_scale.back() = 1 + (i % 7) * 0.25;
                                            m.gamma_scale.back() = 1 + (i % 5) * 0.5;
                                            m.anchor_scale.back() = i % 3 == 0 ? 2.0 : 0.0;
                                            m.fixed.back() = b == 0 && a % 4 == 0;
                                            m.external_force.back() = Vec3(0, -1e-4 * (i % 2), 0);
                                          }),
                       p);
}

State shaken(const Model& model) {
  State s = rest_state(model);
  test::shake(s.x, 0.2, 5);
  return s;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(Step, ForcesAreTheSerialScatterSumsBitForBit) {
  // The reference: one loop over the springs adding +f to i and -f to j (the summation order
  // every node's force must keep on threads).
  Params p;
  const Model m = lattice(p);
  const State s = shaken(m);
  std::vector<Vec3> want(m.spec().rest.size());
  for (size_t i = 0; i < want.size(); ++i)
    want[i] = -m.anchor_kappa[i] * (s.x[i] - m.spec().rest[i]);
  for (size_t k = 0; k < m.spec().springs.size(); ++k) {
    const Spring& sp = m.spec().springs[k];
    const Vec3 delta = s.x[size_t(sp.j)] - s.x[size_t(sp.i)];
    const double l = delta.norm();
    const Vec3 f = (m.spring_kappa[k] * (l - sp.rest_length) / l) * delta;
    want[size_t(sp.i)] += f;
    want[size_t(sp.j)] -= f;
  }
  for (int threads : {1, 2, 3}) {
    SpringPass pass;
    pass.threads.set_threads(threads);
    pass.threads.set_grain(1000);  // split this 9261-node model
    std::vector<Vec3> got;
    EXPECT_EQ(internal_forces(m, s.x, got, &pass), 0);
    EXPECT_TRUE(same_bits(got, want)) << threads << " threads";
  }
}

TEST(Step, ThreadsOwningNodeRangesAddCrossingSpringsInTheSerialOrder) {
  // Each thread owns a range of nodes and computes every spring with an end in it; springs
  // listed far from their nodes, a spring from the last node back to the first (crossing
  // every boundary), a doubled one and springs of zero length (to itself, between
  // coincident nodes) must still land in each node's serial order and be counted once.
  Params p;
  ModelSpec spec = test::cube_lattice(21, 0.5, [](ModelSpec& m, int i, int a, int b, int) {
    m.anchor_scale.back() = i % 3 == 0 ? 2.0 : 0.0;
    m.fixed.back() = b == 0 && a % 4 == 0;
  });
  const int n = static_cast<int>(spec.rest.size());
  add_spring(spec, n - 1, 0);
  add_spring(spec, n - 1, 0, 2.0);
  add_spring(spec, n / 2, n / 2);   // to itself: no direction
  add_spring(spec, 5, n - 7, 0.5);  // first node low, second high
  add_spring(spec, n - 3, 3);
  const int twin = add_node(spec, spec.rest[static_cast<size_t>(n / 3)]);
  add_spring(spec, n / 3, twin);  // coincident nodes: zero length
  add_spring(spec, 7, n / 2 + 1);
  const Model m = compile_model(spec, p);
  State s = shaken(m);
  s.x[static_cast<size_t>(twin)] = s.x[static_cast<size_t>(n / 3)];
  std::vector<Vec3> want_f;
  std::vector<double> want_r;
  SpringPass one;
  ASSERT_EQ(internal_forces(m, s.x, want_f, &one), 2);
  const int compressed = safe_row_sums(m, s.x, want_r, &one);
  EXPECT_GT(compressed, 0);
  for (int threads : {2, 3, 4}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    SpringPass pass;
    pass.threads.set_threads(threads);
    pass.threads.set_grain(1000);
    ASSERT_EQ(pass.threads.chunks(m.spec().springs.size()), threads);
    std::vector<Vec3> f;
    std::vector<double> r;
    EXPECT_EQ(internal_forces(m, s.x, f, &pass), 2);
    EXPECT_EQ(safe_row_sums(m, s.x, r, &pass), compressed);
    EXPECT_TRUE(same_bits(f, want_f));
    EXPECT_TRUE(same_bits(r, want_r));
  }
}

TEST(Step, AnyThreadCountGivesTheSameBits) {
  for (Integrator in : {Integrator::semi_implicit_euler, Integrator::forward_euler,
                        Integrator::verlet, Integrator::rk4}) {
    for (DampingPolicy policy : {DampingPolicy::clamp, DampingPolicy::safe}) {
      for (const bool spec10 : {false, true}) {  // SPEC 10's damping: its safe bound per node
        Params p;
        p.integrator = in;
        p.policy = policy;
        p.dt = 0.02;
        if (spec10) {
          p.kd = 0.002;
          p.rayleigh_mass = 0.01;
          p.rayleigh_stiffness = 0.001;
        }
        const Model m = lattice(p);
        State one = shaken(m);
        StepWorkspace ws1;
        std::vector<StepStats> serial;
        for (int k = 0; k < 15; ++k) serial.push_back(step(m, p, one, ws1));
        for (int threads : {2, 3, 4}) {
          SCOPED_TRACE(std::string(to_string(in)) + " " + to_string(policy) + " " +
                       std::to_string(threads) + " threads");
          State many = shaken(m);
          StepWorkspace ws;
          ws.pass.threads.set_threads(threads);
          ws.pass.threads.set_grain(1000);  // split this 9261-node model
          ASSERT_GE(ws.pass.threads.chunks(m.spec().rest.size()), 2);
          for (int k = 0; k < 15; ++k) {
            const StepStats st = step(m, p, many, ws);
            ASSERT_EQ(std::memcmp(&st.max_displacement, &serial[size_t(k)].max_displacement,
                                  sizeof(double)),
                      0);
            ASSERT_EQ(st.violating, serial[size_t(k)].violating);
            ASSERT_EQ(st.clamped, serial[size_t(k)].clamped);
            ASSERT_EQ(st.unguaranteed, serial[size_t(k)].unguaranteed);
            ASSERT_EQ(st.compressed_springs, serial[size_t(k)].compressed_springs);
            ASSERT_EQ(st.finite, serial[size_t(k)].finite);
          }
          EXPECT_TRUE(same_bits(many.x, one.x));
          EXPECT_TRUE(same_bits(many.v, one.v));
          EXPECT_TRUE(same_bits(ws.gamma_eff, ws1.gamma_eff));
          EXPECT_TRUE(same_bits(ws.safe_bound, ws1.safe_bound));
          EXPECT_GT(serial.back().compressed_springs, 0);
          EXPECT_EQ(!ws.damping.empty(), spec10);
        }
      }
    }
  }
}

}  // namespace
}  // namespace dampbound
