#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// Tests of core/physics/integrate.cpp: every integrator against its own amplification matrix, its
// order of accuracy, the paper's two Euler steps bit for bit, and runs just inside / outside
// each integrator's exact limit on the paper plane.
#include "core/physics/integrate.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <set>
#include <stdexcept>
#include <string>

#include "core/analysis/criteria.hpp"
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/perturbation_growth.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/physics/step.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {
namespace {

const auto& kAll = kIntegrators;

/// x(T) of y'' = -lambda y - c y', y(0) = 1, y'(0) = 0 (underdamped), exact.
double exact_oscillator(double lambda, double c, double t) {
  const double wd = std::sqrt(lambda - c * c / 4);
  return std::exp(-c * t / 2) * (std::cos(wd * t) + (c / (2 * wd)) * std::sin(wd * t));
}

double run_oscillator(Integrator in, double lambda, double c, double T, int n) {
  Params p;
  p.m = 0.002;
  p.kappa = lambda * p.m;
  p.gamma = c * p.m;
  p.dt = T / n;
  p.integrator = in;
  const Model m = single_node_system(p);
  State s = rest_state(m);
  s.x[0].y() = 1;
  StepWorkspace ws;
  for (int k = 0; k < n; ++k) step(m, p, s, ws);
  return s.x[0].y();
}

TEST(IntegratorTraits, OneEntryPerIntegratorNamedAsFlagsSayIt) {
  std::set<std::string> names;
  for (Integrator in : kIntegrators) {
    const IntegratorTraits& t = integrator_traits(in);
    EXPECT_EQ(t.id, in);
    // advance() has a step for it: one step of the oscillator moves the node.
    EXPECT_NE(run_oscillator(in, 1.0, 0.1, 0.2, 2), 1.0) << t.name;
    EXPECT_EQ(parse_integrator(t.name), in) << t.name;
    EXPECT_STREQ(to_string(in), t.name);
    names.insert(t.name);
    // An implicit step is not the paper's and has no Euler velocity update.
    EXPECT_TRUE(!t.implicit || !(t.paper_step || t.euler_velocity_update)) << t.name;
    // The paper's step is an Euler velocity update.
    EXPECT_TRUE(!t.paper_step || t.euler_velocity_update) << t.name;
  }
  EXPECT_EQ(names.size(), std::size(kIntegrators));
  EXPECT_STREQ(to_string(static_cast<Integrator>(99)), "?");
  EXPECT_THROW(integrator_traits(static_cast<Integrator>(99)), std::invalid_argument);
  EXPECT_TRUE(integrator_traits(Integrator::semi_implicit_euler).paper_step);
  // Messages list the table's names (the scene reader, the key table, Python).
  EXPECT_EQ(one_of(integrator_names()),
            "semi-implicit-euler, forward-euler, verlet, rk4 or implicit-euler");
}

TEST(Integrate, EachStepIsItsAmplificationMatrix) {
  // On the single oscillator (linear) one step of every integrator is exactly the 2x2 matrix
  // the linear analysis uses, in every coordinate: integrate.cpp and linear_stability_modes
  // cannot drift apart.
  const double lambda = 3.0, c = 0.8, h = 0.07;
  for (Integrator in : kAll) {
    Params p;
    p.m = 0.01, p.kappa = lambda * p.m, p.gamma = c * p.m, p.dt = h, p.integrator = in;
    const Model m = single_node_system(p);
    State s = rest_state(m);
    s.x[0] = Vec3(0.3, -0.2, 0.5);
    s.v[0] = Vec3(-0.1, 0.4, 0.25);
    const Eigen::Matrix2d G = mode_amplification(in, lambda, c, h);
    Eigen::Matrix2d Gn = Eigen::Matrix2d::Identity();
    const Vec3 x0 = s.x[0], v0 = s.v[0];
    StepWorkspace ws;
    for (int n = 1; n <= 25; ++n) {
      step(m, p, s, ws);
      Gn = G * Gn;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d want = Gn * Eigen::Vector2d(x0[k], v0[k]);
        ASSERT_NEAR(s.x[0][k], want(0), 1e-12) << to_string(in) << " n=" << n;
        ASSERT_NEAR(s.v[0][k], want(1), 1e-12) << to_string(in) << " n=" << n;
      }
    }
  }
}

TEST(Integrate, SemiImplicitClosedFormOfItsRecurrence) {
  // SPEC 7: the paper's step on a mode has characteristic polynomial
  // z^2 - (2 - c dt - lambda dt^2) z + (1 - c dt); x_n = A z1^n + B z2^n. Cases: damped,
  // overdamped, and beyond the limit (growing).
  using C = std::complex<double>;
  for (auto [lambda, c, h] : {std::tuple{1.0, 0.5, 0.05}, {1.0, 12.0, 0.05}, {400.0, 2.0, 0.11}}) {
    const Eigen::Matrix2d G = mode_amplification(Integrator::semi_implicit_euler, lambda, c, h);
    const double b = 2 - c * h - lambda * h * h, q = 1 - c * h;
    EXPECT_NEAR(G.trace(), b, 1e-14);
    EXPECT_NEAR(G.determinant(), q, 1e-14);
    const C disc = std::sqrt(C(b * b - 4 * q)), z1 = (b + disc) / 2.0, z2 = (b - disc) / 2.0;
    const double x0 = 0.4, v0 = -0.3;
    const double x1 = G(0, 0) * x0 + G(0, 1) * v0;
    const C B = (x1 - x0 * z1) / (z2 - z1), A = x0 - B;
    Params p;
    p.m = 0.001, p.kappa = lambda * p.m, p.gamma = c * p.m, p.dt = h;
    const Model m = single_node_system(p);
    State s = rest_state(m);
    s.x[0].z() = x0;
    s.v[0].z() = v0;
    StepWorkspace ws;
    for (int n = 1; n <= 60; ++n) {
      step(m, p, s, ws);
      const double want = (A * std::pow(z1, n) + B * std::pow(z2, n)).real();
      ASSERT_NEAR(s.x[0].z(), want, 1e-10 * (1 + std::abs(want))) << "lambda " << lambda << " n " << n;
    }
  }
}

TEST(Integrate, OrderOfAccuracy) {
  // Error at T = 2 s on y'' = -4 y - 0.5 y'; halving dt divides it by 2^order.
  const double lambda = 4, c = 0.5, T = 2, exact = exact_oscillator(lambda, c, T);
  const std::pair<Integrator, double> expected[] = {
      {Integrator::semi_implicit_euler, 1}, {Integrator::forward_euler, 1},
      {Integrator::verlet, 2}, {Integrator::rk4, 4}, {Integrator::implicit_euler, 1}};
  for (auto [in, order] : expected) {
    const double e1 = std::abs(run_oscillator(in, lambda, c, T, 200) - exact);
    const double e2 = std::abs(run_oscillator(in, lambda, c, T, 400) - exact);
    EXPECT_NEAR(std::log2(e1 / e2), order, 0.1) << to_string(in) << " errors " << e1 << " " << e2;
  }
}

TEST(Integrate, PaperEulerStepsBitForBit) {
  // Eqs. 3-4 (and forward Euler) written out by hand must give the same doubles.
  const SceneSpec s = load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/paper-plane.toml");
  for (Integrator in : {Integrator::semi_implicit_euler, Integrator::forward_euler}) {
    Params p = s.params;
    p.integrator = in;
    p.gamma = 0.0013;
    ModelSpec spec = s.model;
    spec.external_force[5] = Vec3(0.001, 0, -0.002);
    const Model m = compile_model(spec, p);
    State st = initial_state(s), ref;
    StepWorkspace ws;
    for (int k = 0; k < 5; ++k) {
      ref = st;
      step(m, p, st, ws);
      for (size_t i = 0; i < st.x.size(); ++i) {
        const Vec3 a = (ws.force[i] - ws.gamma_eff[i] * ref.v[i] + m.spec().external_force[i]) / m.mass[i];
        Vec3 v = ref.v[i], x = ref.x[i];
        if (in == Integrator::semi_implicit_euler) {
          v += a * p.dt;
          x += v * p.dt;
        } else {
          x += v * p.dt;
          v += a * p.dt;
        }
        ASSERT_EQ(st.x[i], x) << i;
        ASSERT_EQ(st.v[i], v) << i;
      }
    }
  }
}

TEST(Integrate, FixedNodesStayAndZeroLengthSpringsAreCounted) {
  Params p;
  p.dt = 0.05;
  for (Integrator in : kAll) {
    p.integrator = in;
    ModelSpec spec;
    add_node(spec, Vec3::Zero());
    add_node(spec, Vec3(1, 0, 0));
    add_node(spec, Vec3(1, 0, 0));  // on top of node 1: a zero-length spring
    spec.fixed[0] = 1;
    add_spring(spec, 0, 1);
    add_spring(spec, 1, 2);
    const Model m = compile_model(std::move(spec), p);
    State s = rest_state(m);
    s.v[0] = Vec3(1, 1, 1);  // a fixed node's velocity must not move it
    StepWorkspace ws;
    const StepStats st = step(m, p, s, ws);
    EXPECT_EQ(s.x[0], Vec3::Zero()) << to_string(in);
    EXPECT_TRUE(st.finite) << to_string(in);
    EXPECT_GE(st.zero_length_springs, 1) << to_string(in);
  }
}

/// Steps enough for growth by 1e5 at rho (at most 2000), or 300 to watch a decay.
int steps_for(double rho) {
  return rho > 1 ? static_cast<int>(std::min(2000.0, std::ceil(std::log(1e5) / std::log(rho)))) : 300;
}

TEST(Integrate, EachIntegratorDecaysInsideItsLimitAndGrowsOutside) {
  // The paper plane at m = kappa = 0.001, gamma = 0.002, dt = 0.05: each exact limit (dt,
  // and the gamma interval's ends) is crossed by 5% (50% for forward Euler's slow lower end).
  const SceneSpec s = load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/paper-plane.toml");
  for (Integrator in : kAll) {
    Params p = s.params;
    p.integrator = in;
    const Model m = compile_model(s.model, p);
    const ExactStability e = exact_stability(m, m.spec().rest, p);
    ASSERT_EQ(e.method, in == Integrator::implicit_euler ? ExactMethod::unconditional : ExactMethod::per_mode);
    auto check = [&](const char* what, Params q, bool inside, int steps = 0) {
      const Model mq = compile_model(s.model, q);
      const double rho = spectrum_spectral_radius(in, e.spectrum, q.gamma / q.m, q.dt);
      ASSERT_EQ(rho <= 1, inside) << to_string(in) << " " << what << " rho " << rho;
      const double growth = perturbation_growth(mq, q, steps ? steps : steps_for(rho));
      if (inside) EXPECT_LT(growth, 1.0) << to_string(in) << " " << what;
      else EXPECT_GT(growth, 10.0) << to_string(in) << " " << what;
    };
    if (std::isfinite(e.dt_max)) {
      Params q = p;
      q.dt = 0.95 * e.dt_max;
      check("0.95 dt_max", q, true);
      q.dt = 1.05 * e.dt_max;
      check("1.05 dt_max", q, false);
    } else {
      Params q = p;
      q.dt = 20 * 0.5;  // 20x the paper step's limit at this gamma: still decays (rho = 0.09)
      check("dt = 10 s", q, true, 30);
    }
    if (std::isfinite(e.gamma_hi)) {
      Params q = p;
      q.gamma = 0.95 * e.gamma_hi;
      check("0.95 gamma_hi", q, true);
      q.gamma = 1.05 * e.gamma_hi;
      check("1.05 gamma_hi", q, false);
    }
    if (e.gamma_lo > 0) {
      Params q = p;
      q.gamma = 1.05 * e.gamma_lo;
      check("1.05 gamma_lo", q, true);
      q.gamma = 0.5 * e.gamma_lo;
      check("0.5 gamma_lo", q, false);
    }
  }
}

}  // namespace
}  // namespace dampbound
