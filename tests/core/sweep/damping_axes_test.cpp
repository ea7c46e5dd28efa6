// SPEC 10's damping as sweep axes: kd, rayleigh_mass and rayleigh_stiffness vary slowest, enter
// the similarity classes (kd/m with kappa/m and gamma/m; alpha and beta as themselves), reach
// every trial's step(), are written as three more CSV columns and read back; and the sweep's
// closed-form prediction agrees with the certified exact limits of core/analysis.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "core/analysis/damping_limits.hpp"
#include "core/sweep/csv.hpp"
#include "core/sweep/map.hpp"
#include "core/sweep/summary.hpp"
#include "core/sweep/trials.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/error.hpp"
#include "sweep_test_util.hpp"

namespace dampbound {
namespace {

SweepSpec damping_sweep(const SceneSpec& scene) {
  SweepSpec s = test::small_sweep(scene, 120);
  s.gamma_mode = GammaMode::absolute;
  s.m = parse_axis("--m", "0.001,0.002", AxisDomain::positive);
  s.kappa = parse_axis("--kappa", "0.001,0.002", AxisDomain::positive);
  s.gamma = parse_axis("--gamma", "0.002,0.004", AxisDomain::non_negative);
  s.kd = parse_axis("--kd", "0.002,0.004", AxisDomain::non_negative);
  s.rayleigh_mass = parse_axis("--rayleigh-mass", "0", AxisDomain::non_negative);
  s.rayleigh_stiffness = parse_axis("--rayleigh-stiffness", "0,0.5", AxisDomain::non_negative);
  return s;
}

TEST(SweepDampingAxes, VarySlowestAndReachTheTrialsParams) {
  const SceneSpec scene = test::shipped_scene("paper-plane");
  const SweepGrid grid(damping_sweep(scene));
  ASSERT_EQ(grid.trials(), 2u * 2u * 2u * 2u * 2u);
  // The first 8 trials are the m x kappa x gamma block at the first kd and beta.
  for (std::uint64_t t = 0; t < 8; ++t) {
    EXPECT_EQ(grid.index(t).kd, 0u);
    EXPECT_EQ(grid.index(t).rayleigh_stiffness, 0u);
  }
  EXPECT_EQ(grid.index(8).kd, 1u);
  EXPECT_EQ(grid.index(16).rayleigh_stiffness, 1u);
  const TrialParams p = grid.params(31);
  ASSERT_TRUE(p.kd && p.rayleigh_mass && p.rayleigh_stiffness);
  EXPECT_EQ(*p.kd, 0.004);
  EXPECT_EQ(*p.rayleigh_stiffness, 0.5);
  const Params q = trial_params(scene.params, DampingPolicy::fixed, p);
  EXPECT_EQ(q.kd, 0.004);
  EXPECT_EQ(q.rayleigh_stiffness, 0.5);
  // Without the axes a trial keeps the scene's damping.
  SweepSpec plain = damping_sweep(scene);
  plain.kd = plain.rayleigh_mass = plain.rayleigh_stiffness = Axis{};
  const TrialParams r = SweepGrid(plain).params(0);
  EXPECT_FALSE(r.kd || r.rayleigh_mass || r.rayleigh_stiffness);
  Params base = scene.params;
  base.kd = 0.003;
  EXPECT_EQ(trial_params(base, DampingPolicy::fixed, r).kd, 0.003);
}

TEST(SweepDampingAxes, ClassesKeyKdOverMAndTheRayleighCoefficients) {
  const SceneSpec scene = test::shipped_scene("paper-plane");
  const SweepGrid grid(damping_sweep(scene));
  const TrialClasses c = find_classes(grid, similarity_unavailable(scene, true));
  ASSERT_TRUE(c.similarity) << c.reason;
  auto trial = [&](int m, int kappa, int gamma, int kd, int beta) {
    for (std::uint64_t t = 0; t < grid.trials(); ++t) {
      const SweepGrid::Index ix = grid.index(t);
      if (ix.m == size_t(m) && ix.kappa == size_t(kappa) && ix.gamma == size_t(gamma) &&
          ix.kd == size_t(kd) && ix.rayleigh_stiffness == size_t(beta))
        return t;
    }
    ADD_FAILURE();
    return std::uint64_t{0};
  };
  // m, kappa, gamma, kd all doubled: one class (kappa/m, gamma/m, kd/m equal).
  EXPECT_EQ(c.class_of[trial(0, 0, 0, 0, 0)], c.class_of[trial(1, 1, 1, 1, 0)]);
  // kd not doubled with the others: kd/m differs.
  EXPECT_NE(c.class_of[trial(0, 0, 0, 0, 0)], c.class_of[trial(1, 1, 1, 0, 0)]);
  // beta differs: another class even where everything else is similar.
  EXPECT_NE(c.class_of[trial(0, 0, 0, 0, 0)], c.class_of[trial(1, 1, 1, 1, 1)]);
  // A scene's kd that is not an axis is not scaled with m: no similarity.
  SceneSpec held = scene;
  held.params.kd = 0.002;
  EXPECT_TRUE(similarity_unavailable(held).has_value());
  EXPECT_FALSE(similarity_unavailable(held, true).has_value());
}

TEST(SweepDampingAxes, SimilarTrialsAgreeThroughStep) {
  const SceneSpec scene = test::shipped_scene("paper-plane");
  SweepSpec s = damping_sweep(scene);
  const SweepGrid grid(s);
  const TrialClasses c = find_classes(grid, similarity_unavailable(scene, true));
  int compared = 0;
  for (std::uint64_t t = 0; t < grid.trials(); ++t) {
    const std::uint64_t rep = c.representative[c.class_of[t]];
    if (rep == t) continue;
    const TrialResult a = run_reference(scene, s.policy, s.rules, grid.params(rep));
    const TrialResult b = run_reference(scene, s.policy, s.rules, grid.params(t));
    EXPECT_EQ(a.outcome, b.outcome) << "trial " << t;
    EXPECT_LE(std::abs(a.iterations - b.iterations), 1) << "trial " << t;
    ++compared;
  }
  EXPECT_EQ(compared, 2);  // (m, kappa, gamma, kd) doubled together, at each beta
}

TEST(SweepDampingAxes, CsvHasThreeMoreColumnsAndReadsBack) {
  EXPECT_EQ(sweep_csv_columns(StopRule::first_entry, false),
            "trial,m,kappa,gamma,zeta,dt,policy,factor,class,ran,outcome,iterations,"
            "max_displacement,violations,unstabilisable,clamped,zero_length_springs");
  EXPECT_EQ(sweep_csv_columns(StopRule::settled, true),
            "trial,m,kappa,gamma,zeta,dt,policy,factor,kd,rayleigh_mass,rayleigh_stiffness,"
            "class,ran,outcome,iterations,max_displacement,violations,unstabilisable,clamped,"
            "zero_length_springs,first_entry,left_at,settled_at");
  const SceneSpec scene = test::shipped_scene("paper-plane");
  for (StopRule rule : {StopRule::first_entry, StopRule::settled}) {
    SweepSpec s = damping_sweep(scene);
    s.rules.rule = rule;
    const SweepGrid grid(s);
    const TrialClasses c = find_classes(grid, similarity_unavailable(scene, true));
    std::vector<TrialResult> results(c.count());
    for (size_t k = 0; k < results.size(); ++k) {
      results[k].outcome = rule == StopRule::settled ? Outcome::settled : Outcome::restored;
      results[k].iterations = static_cast<int>(k) + 1;
    }
    const std::string path = ::testing::TempDir() + "/damping_axes.csv";
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_TRUE(f);
    SweepHeader h;
    h.sweep_id = "0123456789abcdef";
    h.rule = rule;
    h.damping = true;
    h.trials = grid.trials();
    write_sweep_header(f, h);
    write_sweep_rows(f, grid, c, results, 1, 1);
    std::fclose(f);
    const SweepTable t = read_sweep_csv(path);
    EXPECT_TRUE(t.header.damping);
    ASSERT_EQ(t.rows.size(), grid.trials());
    for (std::uint64_t k = 0; k < grid.trials(); ++k) {
      const TrialParams p = grid.params(k);
      EXPECT_EQ(t.rows[k].kd, *p.kd);
      EXPECT_EQ(t.rows[k].rayleigh_stiffness, *p.rayleigh_stiffness);
      EXPECT_EQ(t.rows[k].iterations, static_cast<int>(c.class_of[k]) + 1);
    }
  }
}

// The closed form the sweep's summary uses (uniform model at rest, dashpots proportional to K)
// against general_limits(), which bisects the certified index lambda_max(dt^2 A + 2 dt C^).
TEST(SweepDampingAxes, ClosedFormMatchesTheExactIndex) {
  const SceneSpec scene = paper_plane_scene(6);  // the paper's plane, 36 nodes: dense eigensolves
  const double lambda_unit = unit_stiffness_eigenvalue(scene);
  const auto ratio = dashpot_stiffness_ratio(scene);
  ASSERT_TRUE(ratio.has_value());
  int checked = 0;
  for (double kd : {0.0, 0.002, 0.01})
    for (double alpha : {0.0, 0.5})
      for (double beta : {0.0, 0.3}) {
        Params p = scene.params;
        p.m = 0.001;
        p.kappa = 0.002;
        p.gamma = 0.002;
        p.kd = kd;
        p.rayleigh_mass = alpha;
        p.rayleigh_stiffness = beta;
        const Model model = compile_model(scene.model, p);
        const GeneralLimits exact = general_limits(model, model.spec().rest, p);
        for (double f : {0.97, 1.03}) {
          SweepRow r;
          r.m = p.m;
          r.kappa = p.kappa;
          r.gamma = p.gamma;
          r.kd = kd;
          r.rayleigh_mass = alpha;
          r.rayleigh_stiffness = beta;
          r.dt = exact.dt_max * f;
          EXPECT_EQ(linearly_unstable(r, lambda_unit, *ratio), f > 1)
              << "kd " << kd << " alpha " << alpha << " beta " << beta << " dt_max "
              << exact.dt_max;
          ++checked;
        }
      }
  EXPECT_EQ(checked, 24);
  // A spring off its rest length breaks the proportionality.
  SceneSpec stretched = scene;
  stretched.model.springs[0].rest_length *= 0.9;
  EXPECT_FALSE(dashpot_stiffness_ratio(stretched).has_value());
}

// map --axes kd:dt: one panel of the rows at the held gamma, and the exact boundary on it is
// the dt limit general_limits() certifies at each kd.
TEST(SweepDampingAxes, MapDrawsAnyTwoColumnsWithTheExactBoundary) {
  const SceneSpec scene = paper_plane_scene(6);  // the paper's plane, 36 nodes: dense eigensolves
  SweepTable t;
  t.header.policy = DampingPolicy::fixed;
  t.header.definition = "policy=fixed max-iter=100";
  t.header.scene_name = "paper-plane";
  t.header.damping = true;
  for (double gamma : {0.0, 0.002})
    for (double kd : {0.0, 0.001, 0.002, 0.003, 0.004})
      for (double dt : {0.02, 0.05, 0.1, 0.2, 0.4}) {
        SweepRow r;
        r.m = r.kappa = 0.001;
        r.gamma = gamma;
        r.zeta = gamma / lower_bound(r.m, r.kappa);
        r.kd = kd;
        r.dt = dt;
        r.outcome = Outcome::restored;
        t.rows.push_back(r);
      }
  MapOptions opt;
  opt.axes = {{"kd", "dt"}, {"gamma", "dt"}};
  opt.dashpot_ratio = dashpot_stiffness_ratio(scene);
  const double lambda_unit = unit_stiffness_eigenvalue(scene);
  const StabilityMap map = build_stability_map(t, lambda_unit, opt);
  ASSERT_EQ(map.panels.size(), 2u);
  const MapPanel& kd_dt = map.panels[0];
  EXPECT_NE(kd_dt.title.find("gamma = 0"), std::string::npos) << kd_dt.title;
  EXPECT_EQ(kd_dt.x_edges.size(), 6u);  // five kd values
  EXPECT_EQ(kd_dt.y_edges.size(), 6u);  // five dt values, at gamma = 0 only
  ASSERT_EQ(kd_dt.lines.size(), 1u);
  const MapLine& line = kd_dt.lines[0];
  int compared = 0;
  for (size_t k = 0; k < line.x.size(); k += 50) {
    if (!std::isfinite(line.y[k]) || line.x[k] <= 0) continue;
    Params p = scene.params;
    p.m = p.kappa = 0.001;
    p.gamma = 0;
    p.kd = line.x[k];
    const Model model = compile_model(scene.model, p);
    const double dt_max = general_limits(model, model.spec().rest, p).dt_max;
    EXPECT_NEAR(line.y[k], dt_max, 1e-6 * dt_max) << "kd " << line.x[k];
    ++compared;
  }
  EXPECT_GE(compared, 4);
  EXPECT_THROW(build_stability_map(t, lambda_unit, MapOptions{{}, {{"kd", "wobble"}}, {}}),
               InputError);
}

}  // namespace
}  // namespace dampbound
