// Linear stability of every integrator (core/analysis/linear_stability_modes.hpp): the 2x2
// mode matrices against their formulas, and the two-node system's known eigenvalues.
// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/linear_stability_modes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/io/scene_file.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

const double kInf = std::numeric_limits<double>::infinity();

void expect_matrix_near(const Eigen::Matrix2d& a, const Eigen::Matrix2d& b) {
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) EXPECT_NEAR(a(r, c), b(r, c), 1e-14) << r << "," << c;
}

TEST(LinearStabilityModes, ModeMatricesFollowTheirFormulas) {
  const double lambda = 3.0, c = 0.5, h = 0.1;
  Eigen::Matrix2d semi, fwd, imp;
  semi << 1 - h * h * lambda, h * (1 - c * h), -h * lambda, 1 - c * h;  // SPEC 7
  fwd << 1, h, -h * lambda, 1 - c * h;
  const double d = 1 + h * c + h * h * lambda;
  imp << 1 - h * h * lambda / d, h / d, -h * lambda / d, 1 / d;
  expect_matrix_near(mode_amplification(Integrator::semi_implicit_euler, lambda, c, h), semi);
  expect_matrix_near(mode_amplification(Integrator::forward_euler, lambda, c, h), fwd);
  expect_matrix_near(mode_amplification(Integrator::implicit_euler, lambda, c, h), imp);
  Eigen::Matrix2d J, term = Eigen::Matrix2d::Identity(), rk4 = Eigen::Matrix2d::Identity();
  J << 0, 1, -lambda, -c;
  for (int k = 1; k <= 4; ++k) {
    term = term * (h * J) / k;
    rk4 += term;
  }
  expect_matrix_near(mode_amplification(Integrator::rk4, lambda, c, h), rk4);
  // Verlet undamped is the leapfrog: [[1 - h^2 l/2, h], [-h l (1 - h^2 l/4), 1 - h^2 l/2]].
  Eigen::Matrix2d leap;
  leap << 1 - h * h * lambda / 2, h, -h * lambda * (1 - h * h * lambda / 4), 1 - h * h * lambda / 2;
  expect_matrix_near(mode_amplification(Integrator::verlet, lambda, 0, h), leap);
}

TEST(LinearStabilityModes, SemiImplicitRadius) {
  // det = 1 - c h; complex eigenvalues (c h small) have |z| = sqrt(1 - c h).
  EXPECT_NEAR(mode_spectral_radius(Integrator::semi_implicit_euler, 1.0, 0.0, 0.5), 1.0, 1e-14);
  EXPECT_NEAR(mode_spectral_radius(Integrator::semi_implicit_euler, 1.0, 0.2, 0.5),
              std::sqrt(0.9), 1e-14);
  // lambda h^2 > 4 - 2 c h: unstable.
  EXPECT_GT(mode_spectral_radius(Integrator::semi_implicit_euler, 1.0, 0.0, 2.1), 1.0);
  // Forward Euler undamped: |z|^2 = 1 + lambda h^2.
  EXPECT_NEAR(mode_spectral_radius(Integrator::forward_euler, 4.0, 0.0, 0.5), std::sqrt(2.0),
              1e-14);
}

TEST(LinearStabilityModes, UniformLimits) {
  const StiffnessSpectrum s{0.5, 1.0};
  // Semi-implicit, c = 2: lambda dt^2 < 4 - 2 c dt -> dt^2 + 4 dt - 4 < 0 -> dt < 2 sqrt 2 - 2.
  EXPECT_NEAR(uniform_dt_max(Integrator::semi_implicit_euler, s, 2.0), 2 * std::sqrt(2.0) - 2,
              1e-12);
  EXPECT_EQ(uniform_dt_max(Integrator::implicit_euler, s, 0.0), kInf);
  EXPECT_EQ(uniform_dt_max(Integrator::forward_euler, s, 0.0), 0.0);
  // Forward Euler with damping: stable up to some dt, and at that dt the radius is 1.
  const double fe = uniform_dt_max(Integrator::forward_euler, s, 1.0);
  EXPECT_GT(fe, 0.0);
  EXPECT_NEAR(spectrum_spectral_radius(Integrator::forward_euler, s, 1.0, fe), 1.0, 1e-9);
  const RateInterval semi = uniform_rate_interval(Integrator::semi_implicit_euler, s, 0.5);
  EXPECT_EQ(semi.lo, 0.0);
  EXPECT_DOUBLE_EQ(semi.hi, (4 - 1.0 * 0.25) / (2 * 0.5));
  EXPECT_TRUE(uniform_rate_interval(Integrator::semi_implicit_euler, s, 2.0).empty());
  EXPECT_EQ(uniform_rate_interval(Integrator::implicit_euler, s, 10.0).hi, kInf);
  // RK4's interval ends where its radius reaches 1.
  const RateInterval rk = uniform_rate_interval(Integrator::rk4, s, 0.5);
  ASSERT_FALSE(rk.empty());
  EXPECT_NEAR(spectrum_spectral_radius(Integrator::rk4, s, rk.hi, 0.5), 1.0, 1e-9);
}

// A mode with lambda < 0 (K indefinite, ExactStability::indefinite) grows under every
// explicit step whatever the damping rate and the step: its characteristic polynomial is
// below 0 at z = 1 (lambda h^2 for the paper's step).
TEST(LinearStabilityModes, ANegativeModeGrowsUnderEveryExplicitStep) {
  for (Integrator in : {Integrator::semi_implicit_euler, Integrator::forward_euler,
                        Integrator::verlet, Integrator::rk4})
    for (double lambda : {-1e-6, -0.01, -1.0, -100.0})
      for (double c : {0.0, 0.1, 1.0, 10.0, 100.0})
        for (double h : {1e-4, 1e-2, 0.1, 0.5, 1.0, 3.0})
          EXPECT_GT(mode_spectral_radius(in, lambda, c, h), 1)
              << to_string(in) << " lambda " << lambda << " c " << c << " h " << h;
}

TEST(LinearStabilityModes, ModeInstabilityOfForwardEulerVerletAndRk4) {
  // mode_instability's thresholds against the 2x2 step's own radius: past each one the mode
  // is unstable (radius above 1 + 1e-12, what the limits count as unstable), and just before
  // it the mode is stable, so each threshold is the boundary, on its unstable side.
  const double unstable = 1 + 1e-12;
  auto rho = [](Integrator i, double lambda, double c, double h) {
    return mode_spectral_radius(i, lambda, c, h);
  };
  for (Integrator i : {Integrator::forward_euler, Integrator::verlet})
    for (double c : {0.0, 0.02, 2.0})
      for (double h : {0.01, 0.05, 0.3}) {
        if (i == Integrator::forward_euler && c == 0) continue;  // unstable at every lambda > 0
        const double lambda_0 = 7.8;
        const ModeInstability m = mode_instability(i, lambda_0, c, h);
        SCOPED_TRACE(std::string(to_string(i)) + " c=" + std::to_string(c) + " h=" +
                     std::to_string(h));
        ASSERT_TRUE(std::isfinite(m.lambda_from));
        for (double f : {1 + 1e-9, 1.01, 2.0, 1e3}) EXPECT_GT(rho(i, m.lambda_from * f, c, h), unstable);
        EXPECT_LE(rho(i, m.lambda_from * (1 - 1e-6), c, h), unstable);
        // dt from which lambda_0 is unstable at c.
        ASSERT_TRUE(std::isfinite(m.dt_from));
        for (double f : {1 + 1e-9, 1.5, 10.0}) EXPECT_GT(rho(i, lambda_0, c, m.dt_from * f), unstable);
        EXPECT_LE(rho(i, lambda_0, c, m.dt_from * (1 - 1e-6)), unstable);
        // Rates up to rate_below are unstable at h (forward Euler: too little damping).
        const bool past = h >= m.dt_from;
        if (i == Integrator::forward_euler) {
          EXPECT_EQ(std::isfinite(m.rate_below), h * h * lambda_0 > 1e-11);
          if (std::isfinite(m.rate_below)) {
            for (double f : {1 - 1e-9, 0.5, 0.0})
              EXPECT_GT(rho(i, lambda_0, m.rate_below * f, h), unstable);
            EXPECT_LE(rho(i, lambda_0, m.rate_below * (1 + 1e-6), h), unstable);
          }
        } else {  // Verlet: no damping helps once h^2 lambda_0 > 4
          EXPECT_EQ(std::isfinite(m.rate_below), past);
          if (past) {
            EXPECT_GT(m.rate_below, 1e6);
          }
        }
        EXPECT_EQ(c <= m.rate_below, past);  // the two thresholds agree at (c, h)
      }
  // Verlet's boundary is SPEC 7's dt < 2/sqrt(lambda) at no damping.
  EXPECT_NEAR(mode_instability(Integrator::verlet, 4.0, 0.0, 0.1).dt_from, 1.0, 1e-9);
  // RK4: a certified lambda from which every mode is unstable (no dt or rate threshold).
  // Undamped, its boundary is |z|^2 = 1 - Y^3/72 + Y^4/576 = 1 at Y = (h w)^2 = 8.
  EXPECT_NEAR(mode_instability(Integrator::rk4, 7.8, 0.0, 0.5).lambda_from, 8 / 0.25, 1e-9);
  for (double c : {0.0, 0.02, 2.0, 20.0})
    for (double h : {0.01, 0.05, 0.3}) {
      const ModeInstability m = mode_instability(Integrator::rk4, 7.8, c, h);
      SCOPED_TRACE("rk4 c=" + std::to_string(c) + " h=" + std::to_string(h));
      EXPECT_TRUE(std::isnan(m.dt_from) && std::isnan(m.rate_below));
      ASSERT_TRUE(std::isfinite(m.lambda_from));
      EXPECT_GE(m.lambda_from, c * c / 4);  // underdamped modes only
      for (int k = 0; k <= 400; ++k) {  // 400 points up to 1e6 times the threshold
        const double lambda = m.lambda_from * (1 + 1e-9) * std::pow(1e6, k / 400.0);
        ASSERT_GT(rho(Integrator::rk4, lambda, c, h), unstable) << lambda;
      }
      // The boundary itself, unless every underdamped mode is unstable (heavy damping).
      if (m.lambda_from > c * c / 4 * (1 + 1e-6)) {
        EXPECT_LE(rho(Integrator::rk4, m.lambda_from * (1 - 1e-6), c, h), unstable);
        const StiffnessSpectrum top{m.lambda_from, m.lambda_from};
        EXPECT_NEAR(uniform_dt_max(Integrator::rk4, top, c), h, 1e-6 * h);  // the same boundary
      } else {
        EXPECT_GT(rho(Integrator::rk4, c * c / 4 * (1 + 1e-9), c, h), unstable);
      }
    }
  // No closed form here for the others.
  for (Integrator i : {Integrator::semi_implicit_euler, Integrator::implicit_euler})
    EXPECT_TRUE(std::isnan(mode_instability(i, 7.8, 2.0, 0.05).lambda_from));
}

TEST(LinearStabilityModes, ModeStabilityOfForwardEulerAndVerlet) {
  // Every mode in [0, lambda_hi] against the 2x2 step's own radius: where mode_stability says
  // stable, none is above 1 + 1e-12; just past each of its thresholds some mode is.
  const double ok = 1 + 1e-12;
  const double lambda_hi = 9;
  auto worst = [&](Integrator i, double c, double h) {
    double r = 0;
    for (int k = 0; k <= 2000; ++k)  // 0, then log-spaced up to lambda_hi
      r = std::max(r, mode_spectral_radius(i, k == 0 ? 0 : lambda_hi * std::pow(1e-6, 1 - k / 2000.0), c, h));
    return r;
  };
  for (Integrator i : {Integrator::forward_euler, Integrator::verlet})
    for (double c : {0.0, 0.5, 2.0, 5.0, 8.0})
      for (double h : {0.01, 0.1, 0.2, 0.3, 0.5}) {
        const ModeStability m = mode_stability(i, lambda_hi, c, h);
        SCOPED_TRACE(std::string(to_string(i)) + " c=" + std::to_string(c) + " h=" +
                     std::to_string(h));
        EXPECT_EQ(m.stable, worst(i, c, h) <= ok);  // exact: the sampled modes include the worst
        if (m.dt_up_to > 0) {
          EXPECT_LE(worst(i, c, m.dt_up_to), ok);
          EXPECT_GT(worst(i, c, m.dt_up_to * (1 + 1e-6)), ok);
        }
        if (m.rate_lo <= m.rate_hi) {
          EXPECT_LE(worst(i, m.rate_lo, h), ok);
          if (std::isfinite(m.rate_hi)) {
            EXPECT_LE(worst(i, m.rate_hi, h), ok);
            EXPECT_GT(worst(i, m.rate_hi * (1 + 1e-6), h), ok);
          }
          if (m.rate_lo > 0) {
            EXPECT_GT(worst(i, m.rate_lo * (1 - 1e-6), h), ok);
          }
        } else {
          EXPECT_GT(worst(i, 0.5 * (m.rate_lo + m.rate_hi), h), ok);
        }
      }
  for (Integrator i : {Integrator::semi_implicit_euler, Integrator::implicit_euler}) {
    EXPECT_FALSE(mode_stability(i, 9, 1, 0.1).proved);
    EXPECT_FALSE(mode_stability(i, 9, 1, 0.1).stable);
  }
}

TEST(LinearStabilityModes, ModeStabilityOfRk4) {
  // RK4's stable side at (c, h), every mode in [0, lambda_hi], against the 2x2 step's own
  // radius at modes from 0 to lambda_hi (log- and evenly spaced, and around c^2/4 where the
  // roots turn complex): where it says stable none is above 1 + 1e-12, and where every sampled
  // mode is below 1 - 1e-9 the proof closes. No threshold in dt or c.
  const double ok = 1 + 1e-12;
  auto worst = [&](double lambda_hi, double c, double h) {
    double r = mode_spectral_radius(Integrator::rk4, 0, c, h);
    for (int k = 0; k <= 2000; ++k) {
      r = std::max(r, mode_spectral_radius(Integrator::rk4,
                                           lambda_hi * std::pow(1e-6, 1 - k / 2000.0), c, h));
      r = std::max(r, mode_spectral_radius(Integrator::rk4, lambda_hi * k / 2000.0, c, h));
      const double q = c * c / 4 * (1 + (k - 1000) * 1e-4);
      if (q > 0 && q <= lambda_hi) r = std::max(r, mode_spectral_radius(Integrator::rk4, q, c, h));
    }
    return r;
  };
  int proved = 0, refused = 0;
  for (double c : {0.0, 0.5, 2.0, 5.0, 8.0, 11.0})
    for (double h : {0.01, 0.1, 0.2, 0.3, 0.5, 0.9, 0.94, 1.0}) {
      const ModeStability m = mode_stability(Integrator::rk4, 9, c, h);
      SCOPED_TRACE("c=" + std::to_string(c) + " h=" + std::to_string(h));
      EXPECT_TRUE(m.proved);
      EXPECT_EQ(m.stable, m.rate_lo <= c && c <= m.rate_hi);  // the rates around c, or none
      const double w = worst(9, c, h);
      if (m.stable) {
        EXPECT_LE(w, ok);
      }
      if (w <= 1 - 1e-9) {
        EXPECT_TRUE(m.stable) << "worst radius " << w;
      }
      (m.stable ? proved : refused) += 1;
    }
  EXPECT_GT(proved, 10);  // both answers occur
  EXPECT_GT(refused, 10);
  // Real roots only (c^2/4 >= lambda_hi): the proof is c h <= 2.78529, RK4's real interval
  // ends at -2.7852936.
  EXPECT_TRUE(mode_stability(Integrator::rk4, 9, 10, 0.278528).stable);
  EXPECT_FALSE(mode_stability(Integrator::rk4, 9, 10, 0.27853).stable);
  EXPECT_GT(mode_spectral_radius(Integrator::rk4, 0, 10, 0.27853), 1 + 1e-12);
  EXPECT_NEAR(mode_stability(Integrator::rk4, 9, 10, 0.1).dt_up_to, 0.278529, 1e-7);
  // The stable side meets the unstable one: the largest lambda_hi proved stable at (c, h)
  // lies just under mode_instability's lambda_from, two certificates from opposite sides.
  for (double c : {0.0, 0.3, 1.0})
    for (double h : {0.05, 0.3, 0.9}) {
      SCOPED_TRACE("c=" + std::to_string(c) + " h=" + std::to_string(h));
      const double from = mode_instability(Integrator::rk4, 1, c, h).lambda_from;
      double lo = from * (1 - 1e-3), hi = from;
      ASSERT_TRUE(mode_stability(Integrator::rk4, lo, c, h).stable);
      ASSERT_FALSE(mode_stability(Integrator::rk4, hi, c, h).stable);
      for (int k = 0; k < 12; ++k) {  // to 2.4e-7 of from
        const double mid = (lo + hi) / 2;
        (mode_stability(Integrator::rk4, mid, c, h).stable ? lo : hi) = mid;
      }
      EXPECT_LE(lo, from);
      EXPECT_GE(lo, from * (1 - 1e-6));
    }
  // And the computed dt limit of a spectrum [0, 9] (uniform_dt_max): proved stable just
  // under it, not just over it; every step up to `dt_up_to` proved, which comes within
  // 2e-6 of it (the real roots' proof stops at 2.78529 of 2.7852936).
  for (double c : {0.0, 0.1, 0.5, 1.0, 2.0, 4.0, 8.0}) {
    SCOPED_TRACE("c=" + std::to_string(c));
    const double dt = uniform_dt_max(Integrator::rk4, StiffnessSpectrum{0, 9}, c);
    if (c <= 2) {
      EXPECT_TRUE(mode_stability(Integrator::rk4, 9, c, dt * (1 - 1e-6)).stable);
      EXPECT_FALSE(mode_stability(Integrator::rk4, 9, c, dt * (1 + 1e-6)).stable);
    }
    const double up_to = mode_stability(Integrator::rk4, 9, c, 0.01).dt_up_to;
    EXPECT_EQ(up_to, mode_stability(Integrator::rk4, 9, c, 0.5).dt_up_to);  // h plays no part
    EXPECT_LE(up_to, dt);
    EXPECT_GE(up_to, dt * (1 - 2e-6));
    for (double f : {1e-3, 0.1, 0.5, 0.9, 0.99, 1.0}) EXPECT_LE(worst(9, c, f * up_to), ok) << f;
    EXPECT_GT(worst(9, c, dt * (1 + 1e-6)), ok);
  }
  // The rates proved stable at a step, against uniform_rate_interval on [0, 9]: inside it,
  // within 2e-6 of its upper end, and no sampled mode unstable at 21 rates across them.
  // At h = 0.96 no rate near 0 is stable (9 h^2 > 8): the range starts above 0.
  struct StepRate {
    double h, c;
  };
  for (const StepRate sr :
       {StepRate{0.05, 0}, StepRate{0.05, 1}, StepRate{0.3, 0}, StepRate{0.3, 1}, StepRate{0.6, 0},
        StepRate{0.6, 1}, StepRate{0.9, 0}, StepRate{0.9, 1}, StepRate{0.96, 1}}) {
    const double h = sr.h, c = sr.c;
    SCOPED_TRACE("h=" + std::to_string(h) + " c=" + std::to_string(c));
    const ModeStability m = mode_stability(Integrator::rk4, 9, c, h);
    const RateInterval computed =
        uniform_rate_interval(Integrator::rk4, StiffnessSpectrum{0, 9}, h);
    ASSERT_TRUE(m.stable);
    EXPECT_GE(m.rate_lo, computed.lo);
    EXPECT_LE(m.rate_hi, computed.hi);
    EXPECT_GE(m.rate_hi, computed.hi * (1 - 2e-6));
    EXPECT_LE(m.rate_lo, computed.lo + 2e-6 * computed.hi);
    if (h > 0.95) {
      EXPECT_GT(m.rate_lo, 0);
    }
    for (int k = 0; k <= 20; ++k)
      EXPECT_LE(worst(9, m.rate_lo + (m.rate_hi - m.rate_lo) * k / 20, h), ok) << k;
  }
  // Where the user's rate is not proved stable, the range grows from the proved sample rate
  // nearest to it, and leaves it out: at h = 0.96 the paper plane's rate 2 (gamma 0.002) is
  // not proved with every mode in [0, 9]; lower rates are.
  const ModeStability far = mode_stability(Integrator::rk4, 9, 2, 0.96);
  EXPECT_TRUE(far.proved);
  EXPECT_FALSE(far.stable);
  ASSERT_LE(far.rate_lo, far.rate_hi);
  EXPECT_TRUE(far.rate_hi < 2 || far.rate_lo > 2) << far.rate_lo << " " << far.rate_hi;
  for (int k = 0; k <= 20; ++k) {
    const double r = far.rate_lo + (far.rate_hi - far.rate_lo) * k / 20;
    EXPECT_LE(worst(9, r, 0.96), ok) << k;
    EXPECT_TRUE(mode_stability(Integrator::rk4, 9, r, 0.96).stable) << k;
  }
  // None: at h = 2 every mode up to 9 has |z| = 6 or a real root past it, outside RK4's region.
  const ModeStability none = mode_stability(Integrator::rk4, 9, 0.5, 2);
  EXPECT_FALSE(none.stable);
  EXPECT_GT(none.rate_lo, none.rate_hi);
}

TEST(LinearStabilityModes, TwoNodeSystemEigenvalues) {
  // Node 1 of scenes/two-node.toml at rest: lambda = kappa/m = 1 along the spring, 0 across
  // it; gamma = 0.002 is critical: c = gamma/m = 2. With h = 0.05 the x mode's trace is
  // 2 - h^2 - c h = 1.8975 and its determinant 1 - c h = 0.9: z = 0.96 and 0.9375. The
  // transverse modes (lambda = 0) give 1 and 0.9, twice.
  const SceneSpec s = load_scene(test::source_path("scenes/two-node.toml"));
  const Model m = compile_model(s.model, s.params);
  const SparseMatrix K = mass_weighted(m, tangent_stiffness(m, m.spec().rest));
  const Eigen::VectorXd rate = damping_rates(m, m.gamma);
  ASSERT_EQ(rate.size(), 3);
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(rate(k), 2.0);
  const Eigen::MatrixXd G = amplification_matrix_dense(Integrator::semi_implicit_euler, K, rate, 0.05);
  ASSERT_EQ(G.rows(), 6);
  Eigen::VectorXcd z = G.eigenvalues();
  std::vector<double> got;
  for (Eigen::Index k = 0; k < z.size(); ++k) {
    EXPECT_NEAR(z(k).imag(), 0.0, 1e-12);
    got.push_back(z(k).real());
  }
  std::sort(got.begin(), got.end());
  const std::vector<double> want = {0.9, 0.9, 0.9375, 0.96, 1.0, 1.0};
  for (size_t k = 0; k < 6; ++k) EXPECT_NEAR(got[k], want[k], 1e-6) << k;
  const SpectralRadius rho =
      amplification_spectral_radius(Integrator::semi_implicit_euler, K, rate, 0.05);
  EXPECT_TRUE(rho.converged);
  EXPECT_NEAR(rho.rho, 1.0, 1e-9);
  // The x mode alone.
  EXPECT_NEAR(mode_spectral_radius(Integrator::semi_implicit_euler, 1.0, 2.0, 0.05), 0.96, 1e-12);
}

}  // namespace
}  // namespace dampbound
