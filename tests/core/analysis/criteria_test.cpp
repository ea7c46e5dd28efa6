// Tests of core/criteria: each criterion's closed form on the two-node system, its verdict
// flipping at its threshold, the paper's bounds at a moving state, the non-uniform
// generalisation (kappa_i = max incident stiffness, K_i = the sum) and how the classic
// criteria compare with the exact limit on the paper plane.
#include "core/analysis/criteria.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/io/scene_file.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/forces.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string source_path(const std::string& rel) { return std::string(DAMPBOUND_SOURCE_DIR) + "/" + rel; }

const CriterionResult& find(const std::vector<CriterionResult>& all, const std::string& prefix) {
  for (const auto& c : all)
    if (c.name.rfind(prefix, 0) == 0) return c;
  throw std::runtime_error("no criterion " + prefix);
}

std::vector<CriterionResult> two_node_criteria(const Params& p) {
  const Model m = two_node_system(p);
  const State rest = rest_state(m);
  return all_criteria(m, rest, p, exact_stability(m, rest.x, p));
}

TEST(Criteria, TwoNodeClosedForms) {
  Params p;
  p.m = 0.003;
  p.kappa = 0.02;
  p.gamma = 0.004;
  p.dt = 0.05;
  const auto all = two_node_criteria(p);
  ASSERT_EQ(all.size(), 13u);
  EXPECT_NEAR(find(all, "paper lower").value, 2 * std::sqrt(p.m * p.kappa), 1e-15);
  EXPECT_NEAR(find(all, "Delingette").value, p.m / (kPi * kPi * p.dt * p.dt), 1e-12);
  EXPECT_NEAR(find(all, "Provot").value, kPi * std::sqrt(p.m / p.kappa), 1e-12);
  EXPECT_NEAR(find(all, "Kacic").value, 2 * std::sqrt(p.m / p.kappa), 1e-12);
  EXPECT_NEAR(find(all, "exact lambda_max").value, p.kappa / p.m, 1e-12);
  // SPEC 7: gamma < 2 m/dt - m lambda dt / 2 and dt < (sqrt(c^2 + 4 lambda) - c)/lambda.
  EXPECT_NEAR(find(all, "exact gamma interval").value, 2 * p.m / p.dt - p.kappa * p.dt / 2, 1e-12);
  const double lambda = p.kappa / p.m, c = p.gamma / p.m;
  EXPECT_NEAR(find(all, "exact dt limit").value, (std::sqrt(c * c + 4 * lambda) - c) / lambda, 1e-12);
  EXPECT_EQ(find(all, "paper upper").verdict, CriterionVerdict::not_applicable);  // at rest
  // SPEC 9 on one spring: A is kappa/m on one row, so Gershgorin is exact.
  EXPECT_NEAR(find(all, "safe damping bound").value, 2 * p.m / p.dt - p.kappa * p.dt / 2, 1e-12);
  EXPECT_NEAR(find(all, "safe dt bound").value, (std::sqrt(c * c + 4 * lambda) - c) / lambda, 1e-12);
  EXPECT_EQ(find(all, "safe check").verdict, CriterionVerdict::within);
  for (const auto& cr : all) EXPECT_FALSE(cr.formula.empty() || cr.source.empty()) << cr.name;
}

TEST(Criteria, AnEmptyGammaIntervalSaysSo) {
  Params p;  // m = kappa = 0.001
  p.dt = 3;  // beyond every gamma under forward Euler (c dt <= 2 and c >= dt lambda clash)
  p.integrator = Integrator::forward_euler;
  const auto beyond = two_node_criteria(p);
  const CriterionResult& empty = find(beyond, "exact gamma interval");
  EXPECT_EQ(empty.verdict, CriterionVerdict::beyond);
  EXPECT_NE(empty.test.find("): empty, no gamma is stable at this dt"), std::string::npos)
      << empty.test;
  p.dt = 0.05;
  p.integrator = Integrator::semi_implicit_euler;
  const auto within = two_node_criteria(p);
  const CriterionResult& some = find(within, "exact gamma interval");
  EXPECT_EQ(some.test.find("empty"), std::string::npos) << some.test;
}

TEST(Criteria, AnOnlyBracketedSpectrumShowsItsRangeAndDecidesOnlyWhatItProves) {
  // Where a certificate fails, an end of the spectrum is only bracketed (ExactStability::
  // Inner): here lambda_max of the two-node system (1) is taken as certified in [1, 1.3].
  // At c = 2 the step is stable for dt < 2 sqrt 2 - 2 = 0.8284 at lambda 1, and for
  // dt < (sqrt 9.2 - 2)/1.3 = 0.7947309 at 1.3: a dt between is undecided, not BEYOND.
  struct Case {
    double dt;
    CriterionVerdict verdict;
  };
  for (const Case k :
       {Case{0.5, CriterionVerdict::within}, Case{0.81, CriterionVerdict::not_applicable},
        Case{0.9, CriterionVerdict::beyond}}) {
    Params p;  // m = kappa = 0.001
    p.gamma = 0.002;
    p.dt = k.dt;
    SCOPED_TRACE(k.dt);
    const Model m = two_node_system(p);
    ExactStability e = exact_stability(m, rest_state(m).x, p);
    ASSERT_EQ(e.method, ExactMethod::per_mode);
    const auto narrow = exact_criteria(e, p);
    for (const auto& row : narrow)
      EXPECT_EQ(row.test.find("bracketed"), std::string::npos) << row.test;
    // The true numbers become the inner ends' and the outer ones are taken at lambda 1.3.
    e.inner = {e.spectral_radius, e.gamma_lo, e.gamma_hi, e.dt_max, e.stable};
    e.lambda_max_lo = e.spectrum.lambda_max;
    e.spectrum.lambda_max = e.decaying.lambda_max = 1.3 * e.lambda_max_lo;
    const double c = p.gamma / p.m;
    e.spectral_radius = spectrum_spectral_radius(e.integrator, e.decaying, c, p.dt);
    e.dt_max = uniform_dt_max(e.integrator, e.spectrum, c);
    e.gamma_hi = uniform_rate_interval(e.integrator, e.spectrum, p.dt).hi * p.m;
    e.stable = p.dt <= e.dt_max;
    ASSERT_NEAR(e.dt_max, (std::sqrt(9.2) - 2) / 1.3, 1e-12);
    const auto wide = exact_criteria(e, p);
    for (const char* prefix : {"exact spectral radius", "exact gamma interval", "exact dt limit"}) {
      const CriterionResult& row = find(wide, prefix);
      // At dt = 0.5 (c dt = 1) a mode's roots are 0 and 1 - lambda dt^2: the radius is the
      // decaying bottom's, lambda = 1, whichever top, and its row shows no bracket.
      if (k.dt == 0.5 && row.name.rfind("exact spectral radius", 0) == 0) {
        EXPECT_EQ(row.test,
                  "rho = 0.75 <= 1 (zero modes, lambda = 0, excluded: z = 1 for any gamma, dt)");
        continue;
      }
      EXPECT_EQ(row.verdict, k.verdict) << row.test;
      EXPECT_NE(row.test.find("an end of the spectrum is only bracketed"), std::string::npos)
          << row.test;
      EXPECT_EQ(row.test.find("undecided") != std::string::npos,
                k.verdict == CriterionVerdict::not_applicable)
          << row.test;
    }
    EXPECT_NE(find(wide, "exact dt limit").test.find("dt_max in [0.79473091, 0.82842712]"),
              std::string::npos)
        << find(wide, "exact dt limit").test;
    // gamma_hi = m (4 - lambda dt^2)/(2 dt): 0.0020637 at lambda 1 and 0.0019426 at 1.3 (dt 0.81).
    EXPECT_NE(find(wide, "exact gamma interval").test.find("lies within [0, "), std::string::npos);
  }
}

TEST(Criteria, VerdictsFlipAtTheirThresholds) {
  Params p;
  p.m = 0.001;
  p.kappa = 0.001;
  p.gamma = 0;
  auto verdict = [&](const char* name, double dt, double gamma) {
    Params q = p;
    q.dt = dt;
    q.gamma = gamma;
    return find(two_node_criteria(q), name).verdict;
  };
  const double ka = 2 * std::sqrt(p.m / p.kappa), t0 = kPi * std::sqrt(p.m / p.kappa);
  const double dt_d = std::sqrt(p.m / (kPi * kPi * p.kappa));  // kappa = k_c(dt)
  EXPECT_EQ(verdict("Kacic", 0.999 * ka, 0), CriterionVerdict::within);
  EXPECT_EQ(verdict("Kacic", 1.001 * ka, 0), CriterionVerdict::beyond);
  EXPECT_EQ(verdict("Provot", 0.999 * t0, 0), CriterionVerdict::within);
  EXPECT_EQ(verdict("Provot", 1.001 * t0, 0), CriterionVerdict::beyond);
  EXPECT_EQ(verdict("Delingette", 0.999 * dt_d, 0), CriterionVerdict::within);
  EXPECT_EQ(verdict("Delingette", 1.001 * dt_d, 0), CriterionVerdict::beyond);
  // On one spring the exact undamped limit is Kacic-Alesic's: dt < 2 sqrt(m/kappa).
  EXPECT_EQ(verdict("exact dt limit", 0.999 * ka, 0), CriterionVerdict::within);
  EXPECT_EQ(verdict("exact dt limit", 1.001 * ka, 0), CriterionVerdict::beyond);
  const double lo = 2 * std::sqrt(p.m * p.kappa), hi = 2 * p.m / 0.05 - p.kappa * 0.05 / 2;
  EXPECT_EQ(verdict("paper lower", 0.05, lo), CriterionVerdict::within);
  EXPECT_EQ(verdict("paper lower", 0.05, 0.999 * lo), CriterionVerdict::beyond);
  EXPECT_EQ(verdict("exact gamma", 0.05, 0.999 * hi), CriterionVerdict::within);
  EXPECT_EQ(verdict("exact gamma", 0.05, 1.001 * hi), CriterionVerdict::beyond);
  EXPECT_EQ(verdict("exact spectral", 0.05, 0.999 * hi), CriterionVerdict::within);
  EXPECT_EQ(verdict("exact spectral", 0.05, 1.001 * hi), CriterionVerdict::beyond);
}

TEST(Criteria, PaperBoundsAtAMovingState) {
  Params p;
  p.m = 0.001;
  p.kappa = 1;
  p.gamma = 0.01;
  p.dt = 0.05;
  const Model m = two_node_system(p);
  State s = rest_state(m);
  s.x[1].x() = 1.02;  // stretched: F = -0.02 along x
  s.v[1] = Vec3(1, 0, 0);
  std::vector<Vec3> f;
  internal_forces(m, s.x, f);
  const auto all = paper_criteria(m, s, p);
  const double hi = upper_bound(s.v[1], f[1], p.m, p.dt);
  EXPECT_NEAR(find(all, "paper upper").value, hi, 1e-15);
  EXPECT_EQ(find(all, "paper upper").node, 1);
  // gamma_lo = 2 sqrt(0.001) = 0.063 > gamma_hi = |0.02 - 0.02| / 1 ~ 0: unstabilisable.
  EXPECT_EQ(find(all, "paper runtime").value, 1);
  EXPECT_EQ(find(all, "paper runtime").verdict, CriterionVerdict::beyond);
}

TEST(Criteria, NonUniformGeneralisation) {
  // stiff-region.toml: a square of nodes (a, b in 12..24) 4x heavier, springs inside it and
  // its anchors 10x stiffer. kappa_i = max incident stiffness (SPEC 3), K_i = the sum.
  const SceneSpec s = load_scene(source_path("scenes/stiff-region.toml"));
  Params p = s.params;
  p.gamma = 0.005;
  const Model m = compile_model(s.model, p);
  auto node = [](int a, int b) { return static_cast<size_t>(a * 36 + b); };
  const double k = p.kappa;
  EXPECT_DOUBLE_EQ(m.node_kappa[node(18, 18)], 10 * k);
  EXPECT_DOUBLE_EQ(m.node_kappa[node(12, 18)], 10 * k);  // on the edge: inner springs 10x
  EXPECT_DOUBLE_EQ(m.node_kappa[node(11, 18)], k);       // outside: springs across the edge 1x
  EXPECT_NEAR(m.lower_bound[node(18, 18)], 2 * std::sqrt(4 * p.m * 10 * k), 1e-15);
  const std::vector<double> K = combined_stiffness(m);
  EXPECT_NEAR(K[node(18, 18)], 6 * 10 * k + 10 * k, 1e-15);      // 6 springs + anchor
  EXPECT_NEAR(K[node(12, 18)], 4 * 10 * k + 2 * k + 10 * k, 1e-15);
  EXPECT_NEAR(K[node(0, 5)], 4 * k + k, 1e-15);  // border node outside: 3 edges, 1 diagonal
  const State rest = rest_state(m);
  const auto all = all_criteria(m, rest, p, exact_stability(m, rest.x, p, {false}));
  const CriterionResult& lo = find(all, "paper lower");
  EXPECT_NEAR(lo.value, 2 * std::sqrt(4 * p.m * 10 * k), 1e-15);  // the worst node is inside
  EXPECT_EQ(lo.verdict, CriterionVerdict::beyond);                 // gamma 0.005 < 0.0126
  EXPECT_NEAR(find(all, "Kacic").value, 2 * std::sqrt(4 * p.m / (70 * k)), 1e-12);
  EXPECT_NEAR(find(all, "Provot").value, kPi * std::sqrt(4 * p.m / (10 * k)), 1e-12);
}

TEST(Criteria, ClassicCriteriaAgainstTheExactLimitOnThePaperPlane) {
  // Undamped, lambda_max = 7.812 kappa/m: the exact limit is dt < 2/sqrt(7.812) = 0.7155 s.
  // Kacic-Alesic (2 sqrt(m/7 kappa) = 0.7559 s) and Provot (pi s) accept dt = 0.73 s, which
  // is unstable; Delingette (dt < 1/pi s) is 2.2x too cautious.
  const SceneSpec s = load_scene(source_path("scenes/paper-plane.toml"));
  Params p = s.params;
  p.gamma = 0;
  p.dt = 0.73;
  const Model m = compile_model(s.model, p);
  const State rest = rest_state(m);
  const auto all = all_criteria(m, rest, p, exact_stability(m, rest.x, p));
  EXPECT_EQ(find(all, "Kacic").verdict, CriterionVerdict::within);
  EXPECT_EQ(find(all, "Provot").verdict, CriterionVerdict::within);
  EXPECT_EQ(find(all, "Delingette").verdict, CriterionVerdict::beyond);
  EXPECT_EQ(find(all, "exact dt limit").verdict, CriterionVerdict::beyond);
  EXPECT_NEAR(find(all, "exact dt limit").value, 2 / std::sqrt(7.8123249218733), 1e-9);
  EXPECT_NEAR(find(all, "Kacic").value, 2 * std::sqrt(1.0 / 7), 1e-12);
}

TEST(Criteria, ExactRowsOverTheFactorisationBudgetGiveNoVerdictBetweenTheProofs) {
  Params p;
  const Model m = compile_model(make_grid(GridSpec{14, 14, 0.57, true, true}), p);
  const State rest = rest_state(m);
  ExactOptions tight;
  tight.max_factor_flops = 1;
  // Between SPEC 9's safe bound (Gershgorin on the index matrix: 0.039775) and the gamma
  // from which Lanczos proves instability (just above the exact 0.03980...): neither proof
  // reaches it.
  Params between = p;
  between.gamma = 0.03979;
  const Model mb = compile_model(make_grid(GridSpec{14, 14, 0.57, true, true}), between);
  const auto all = all_criteria(mb, rest, between, exact_stability(mb, rest.x, between, tight));
  int exact_rows = 0;
  for (const auto& c : all) {
    if (c.name.rfind("exact", 0) == 0) {
      ++exact_rows;
      EXPECT_EQ(c.verdict, CriterionVerdict::not_applicable) << c.name;
      EXPECT_TRUE(std::isnan(c.value)) << c.name;
      EXPECT_EQ(c.test.rfind("not computed: one factorisation would take", 0), 0u) << c.test;
    }
    // The safe rows still judge, without a ratio to an exact limit that was not computed.
    if (c.name.rfind("safe", 0) == 0) {
      EXPECT_EQ(c.test.find("exact limit"), std::string::npos) << c.test;
    }
  }
  EXPECT_EQ(exact_rows, 4);
  EXPECT_EQ(find(all, "safe damping").verdict, CriterionVerdict::beyond);
  EXPECT_NE(find(all, "exact lambda_max").test.find("lambda_max in ["), std::string::npos)
      << find(all, "exact lambda_max").test;
  EXPECT_NE(find(all, "exact gamma interval")
                .test.find("every gamma <= 0.039775 is stable; gamma = "
                           "0.03979 is not proved either way"),
            std::string::npos)
      << find(all, "exact gamma interval").test;
  EXPECT_NE(find(all, "exact spectral radius").test.find(", which proves nothing"),
            std::string::npos)
      << find(all, "exact spectral radius").test;

  // At the default gamma (0.002) the same bound proves the step stable: each exact row says
  // within, as the safe rows do, and names the dts and gammas it proves.
  const auto at = all_criteria(m, rest, p, exact_stability(m, rest.x, p, tight));
  for (const char* name : {"exact spectral radius", "exact gamma interval", "exact dt limit"})
    EXPECT_EQ(find(at, name).verdict, CriterionVerdict::within) << find(at, name).test;
  EXPECT_NE(find(at, "exact spectral radius").test.find(" < 4: stable (proved)"),
            std::string::npos);
  EXPECT_NE(find(at, "exact dt limit").test.find("is stable; dt = 0.05 is stable"),
            std::string::npos)
      << find(at, "exact dt limit").test;
}

TEST(Criteria, OverTheBudgetAStepProvedUnstableWithoutAFactorisationIsBeyond) {
  Params p;
  const Model m = compile_model(make_grid(GridSpec{14, 14, 0.57, true, true}), p);
  const State rest = rest_state(m);
  ExactOptions tight;
  tight.max_factor_flops = 1;
  // Past the exact dt limit (by 1 %): proved unstable, with no factorisation.
  const ExactStability free = exact_stability(m, rest.x, p);
  Params past = p;
  past.dt = 1.01 * free.dt_max;
  const auto beyond = all_criteria(m, rest, past, exact_stability(m, rest.x, past, tight));
  for (const char* row : {"exact spectral radius", "exact dt limit"}) {
    EXPECT_EQ(find(beyond, row).verdict, CriterionVerdict::beyond) << row;
    EXPECT_EQ(find(beyond, row).test.rfind("not computed: one factorisation would take", 0), 0u);
  }
  EXPECT_NE(find(beyond, "exact spectral radius").test.find(">= 4: unstable (proved)"),
            std::string::npos);
  // No damping anywhere (every gamma_scale 0): no gamma can be proved unstable.
  ModelSpec undamped = make_grid(GridSpec{14, 14, 0.57, true, true});
  std::fill(undamped.gamma_scale.begin(), undamped.gamma_scale.end(), 0.0);
  const Model u = compile_model(undamped, p);
  const auto none = all_criteria(u, rest_state(u), p, exact_stability(u, u.spec().rest, p, tight));
  EXPECT_NE(find(none, "exact gamma interval").test.find("no gamma is proved unstable at this dt"),
            std::string::npos)
      << find(none, "exact gamma interval").test;
  // Forward Euler on that mesh is unstable whatever gamma: no rate damps it.
  Params fe = p;
  fe.integrator = Integrator::forward_euler;
  const auto any = all_criteria(u, rest_state(u), fe, exact_stability(u, u.spec().rest, fe, tight));
  EXPECT_EQ(find(any, "exact gamma interval").verdict, CriterionVerdict::beyond);
  EXPECT_NE(find(any, "exact gamma interval").test.find("every gamma is unstable at this dt"),
            std::string::npos)
      << find(any, "exact gamma interval").test;
  EXPECT_EQ(find(any, "exact spectral radius").verdict, CriterionVerdict::beyond);
  // Forward Euler and Verlet (uniform gamma/m): the same from their per-mode closed forms.
  // Forward Euler fails with too little damping: gamma 1 % under its exact gamma_lo.
  for (Integrator i : {Integrator::forward_euler, Integrator::verlet, Integrator::rk4}) {
    Params q = p;
    q.integrator = i;
    const ExactStability computed = exact_stability(m, rest.x, q);
    Params over = q;
    over.dt = 1.01 * computed.dt_max;
    const auto rows = all_criteria(m, rest, over, exact_stability(m, rest.x, over, tight));
    for (const char* row : {"exact spectral radius", "exact gamma interval", "exact dt limit"}) {
      if (i == Integrator::forward_euler && std::string(row) == "exact gamma interval") continue;
      EXPECT_EQ(find(rows, row).verdict, CriterionVerdict::beyond) << to_string(i) << " " << row;
    }
    EXPECT_NE(find(rows, "exact spectral radius").test.find(": unstable (proved)"),
              std::string::npos);
    // At the scene's dt each is proved stable (K >= 0 at rest, every mode below
    // Gershgorin's bound); RK4's gamma and dt rows add the gammas and dts proved stable.
    const auto within = all_criteria(m, rest, q, exact_stability(m, rest.x, q, tight));
    for (const char* row : {"exact spectral radius", "exact gamma interval", "exact dt limit"})
      EXPECT_EQ(find(within, row).verdict, CriterionVerdict::within)
          << to_string(i) << " " << row << ": " << find(within, row).test;
    EXPECT_NE(find(within, "exact spectral radius").test.find("stable (proved)"),
              std::string::npos);
    if (i == Integrator::rk4) {
      EXPECT_NE(
          find(within, "exact gamma interval").test.find("is stable; gamma = 0.002 is stable"),
          std::string::npos)
          << find(within, "exact gamma interval").test;
      EXPECT_NE(find(within, "exact dt limit").test.find("every dt <= 0.929674 is stable"),
                std::string::npos)
          << find(within, "exact dt limit").test;
      // Between the two certificates (Gershgorin's 9 against lambda_max 7.8123): neither.
      Params between = q;
      between.dt = 0.95 * computed.dt_max;
      const auto open = all_criteria(m, rest, between, exact_stability(m, rest.x, between, tight));
      EXPECT_EQ(find(open, "exact dt limit").verdict, CriterionVerdict::not_applicable);
    }
    if (i != Integrator::forward_euler) continue;
    Params weak = q;
    weak.gamma = 0.99 * computed.gamma_lo;
    const auto low = all_criteria(m, rest, weak, exact_stability(m, rest.x, weak, tight));
    EXPECT_EQ(find(low, "exact gamma interval").verdict, CriterionVerdict::beyond);
    EXPECT_NE(find(low, "exact gamma interval").test.find("every gamma <= "), std::string::npos);
  }
}

}  // namespace
}  // namespace dampbound
