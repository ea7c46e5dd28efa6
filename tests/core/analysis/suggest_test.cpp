// Tests of core/suggest: the damping range and its ends, the fastest-settling damping, the
// largest stable dt, the empty case, and the non-uniform (per node class) case, each checked
// against the exact analysis and by the verification runs.
#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/suggest.hpp"
#include "core/io/scene_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace dampbound {
namespace {

constexpr double kPi = 3.14159265358979323846;

SceneSpec scene(const std::string& name) {
  return load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/" + name + ".toml");
}

TEST(Suggest, PaperPlaneDampingRangeAndFastestSettling) {
  const SceneSpec s = scene("paper-plane");
  const DampingSuggestion d = suggest_damping(s, s.params, s.rules);
  ASSERT_FALSE(d.empty);
  EXPECT_NEAR(d.gamma_min, 0.002, 1e-15);  // eq. 5: 2 sqrt(m kappa)
  EXPECT_NEAR(d.gamma_max, 2 * 0.001 / 0.05 - 0.001 * 7.8123249218733 * 0.05 / 2, 1e-10);
  EXPECT_TRUE(d.dt_accepted);
  ASSERT_EQ(d.classes.size(), 1u);
  EXPECT_EQ(d.classes[0].count, 1296);
  // The best gamma has the smallest spectral radius over the range (sampled check).
  ASSERT_GE(d.gamma_best, d.gamma_min);
  ASSERT_LT(d.gamma_best, d.gamma_max);
  const StiffnessSpectrum& sp = d.exact.decaying;
  for (int k = 0; k <= 50; ++k) {
    const double g = d.gamma_min + (d.gamma_max - d.gamma_min) * k / 51;
    EXPECT_LE(d.best_rho, spectrum_spectral_radius(Integrator::semi_implicit_euler, sp, g / 0.001, 0.05) + 1e-12);
  }
  ASSERT_EQ(d.runs.size(), 3u);
  // Verified by the settled rule (SPEC 8): it stays below the band to the limit.
  EXPECT_EQ(d.runs[0].result.outcome, Outcome::settled);
  EXPECT_TRUE(d.runs[0].verified());
  EXPECT_EQ(d.runs[0].rules.rule, StopRule::settled);
  for (const VerifiedRun& r : d.runs) EXPECT_NE(r.result.outcome, Outcome::diverged) << r.label;
}

// SuggestOptions::progress sees every stage in order, with a total that ends at the count of
// stages run; returning false stops the call before the next stage.
TEST(Suggest, ProgressCountsTheStagesAndCanStopThem) {
  const SceneSpec s = scene("paper-plane");
  std::vector<std::string> seen;
  int last_total = 0;
  SuggestOptions o;
  o.progress = [&](int done, int total, const std::string& next) {
    EXPECT_EQ(done, int(seen.size()));
    EXPECT_LT(done, total);
    seen.push_back(next);
    last_total = total;
    return true;
  };
  const DampingSuggestion d = suggest_damping(s, s.params, s.rules, o);
  ASSERT_EQ(seen.size(), 1 + d.runs.size());  // the exact analysis, then each verifying run
  EXPECT_EQ(last_total, int(seen.size()));
  EXPECT_EQ(seen[0], "exact limits at this dt");
  seen.clear();
  const StepSuggestion t = suggest_step(s, s.params, s.rules, o);
  EXPECT_EQ(seen.size(), 1 + t.runs.size());
  // Stop at the second stage: the first verifying run never starts.
  int calls = 0;
  o.progress = [&](int done, int, const std::string&) {
    ++calls;
    return done < 1;
  };
  EXPECT_THROW(suggest_damping(s, s.params, s.rules, o), SuggestCancelled);
  EXPECT_EQ(calls, 2);
}

TEST(Suggest, LargestStableStep) {
  const SceneSpec s = scene("paper-plane");
  const StepSuggestion t = suggest_step(s, s.params, s.rules);  // gamma = 0.002
  const double lambda = 7.8123249218733, c = 2.0;
  EXPECT_NEAR(t.dt_exact, (std::sqrt(c * c + 4 * lambda) - c) / lambda, 1e-9);
  // Delingette is the most cautious here: dt < sqrt(m / (pi^2 kappa)) = 1/pi s.
  EXPECT_NEAR(t.dt_all, 1 / kPi, 1e-12);
  EXPECT_EQ(t.dt_all_by, "Delingette critical stiffness");
  ASSERT_EQ(t.runs.size(), 2u);
  for (const VerifiedRun& r : t.runs) EXPECT_TRUE(r.verified()) << r.label;
  // Beyond the exact limit the same run diverges: the suggestion is not merely cautious.
  const VerifiedRun beyond = verify_run(s, [&] { Params p = s.params; p.dt = 1.05 * t.dt_exact; return p; }(), s.rules, "");
  EXPECT_EQ(beyond.result.outcome, Outcome::diverged);
}

TEST(Suggest, EmptyRangeSaysWhichDtWouldDo) {
  const SceneSpec s = scene("paper-plane");
  Params p = s.params;
  p.dt = 0.6;  // eq. 5 wants gamma >= 0.002, the exact limit allows < 0.00099
  const DampingSuggestion d = suggest_damping(s, p, s.rules);
  EXPECT_TRUE(d.empty);
  EXPECT_TRUE(d.runs.empty());
  EXPECT_NEAR(d.dt_max_at_gamma_min, 0.50396163826, 1e-9);
  EXPECT_FALSE(d.dt_accepted);  // Delingette rejects dt = 0.6
}

TEST(Suggest, NonUniformModelPerNodeClasses) {
  const SceneSpec s = scene("stiff-region");
  SuggestOptions o;
  o.trials = 6;  // keep the test short: 6 + 9 trial runs
  StopRules rules = s.rules;
  rules.max_iterations = 400;  // each settled-rule run goes to its limit (SPEC 8)
  const DampingSuggestion d = suggest_damping(s, s.params, rules, o);
  ASSERT_FALSE(d.empty);
  EXPECT_FALSE(d.exact.uniform_rate);
  // Two classes: the square (m_i = 4m, kappa_i = 10 kappa) and the rest; eq. 5 is set by the
  // square: 2 sqrt(0.004 * 0.01).
  ASSERT_EQ(d.classes.size(), 2u);
  int total = 0;
  for (const NodeClass& c : d.classes) total += c.count;
  EXPECT_EQ(total, 1296);
  EXPECT_NEAR(d.gamma_min, 2 * std::sqrt(0.004 * 0.01), 1e-15);
  EXPECT_NEAR(d.gamma_max, d.exact.gamma_hi, 0);
  EXPECT_TRUE(std::isnan(d.best_rho));  // chosen by trial runs
  EXPECT_GE(d.gamma_best, d.gamma_min);
  EXPECT_LT(d.gamma_best, d.gamma_max);
  ASSERT_FALSE(d.runs.empty());
  EXPECT_EQ(d.runs[0].result.outcome, Outcome::settled);
  EXPECT_TRUE(d.runs[0].verified());
  // No trial in the first pass settled sooner than the chosen value.
  for (int k = 0; k < 6; ++k) {
    const double g = d.gamma_min + (d.gamma_max - d.gamma_min) * (1 - 1e-9) * k / 5;
    Params p = s.params;
    p.gamma = g;
    const RunResult r = verify_run(s, p, rules, "").result;
    if (r.outcome == Outcome::settled) {
      EXPECT_GE(r.settled_at, d.runs[0].result.settled_at) << g;
    }
  }
}

TEST(Suggest, ARunThatEntersAndLeavesIsNotVerified) {
  // Past the exact limit the paper plane enters the band at 12 and leaves it at 63.
  const SceneSpec s = scene("paper-plane");
  Params p = s.params;
  p.dt = 0.51;
  const VerifiedRun r = verify_run(s, p, s.rules, "past the limit");
  EXPECT_EQ(r.result.first_entry, 12);
  EXPECT_FALSE(r.verified());
  p.dt = 0.05;
  EXPECT_TRUE(verify_run(s, p, s.rules, "at the lower bound").verified());
}

TEST(Suggest, UnboundedRangeForVerlet) {
  const SceneSpec s = scene("paper-plane");
  Params p = s.params;
  p.integrator = Integrator::verlet;
  SuggestOptions o;
  o.verify = false;
  const DampingSuggestion d = suggest_damping(s, p, s.rules, o);
  EXPECT_TRUE(std::isinf(d.gamma_max));
  EXPECT_TRUE(std::isfinite(d.gamma_best));
  EXPECT_GE(d.gamma_best, d.gamma_min);
}

// Over the factorisation budget the suggestions come from what is proved without one: the
// range ends where SPEC 9's Gershgorin proof does, inside the exact range, every gamma in it
// exactly stable, and the exact limit inside the bracket it prints; the step likewise.
TEST(Suggest, OverTheBudgetWhatIsProvedIsSuggested) {
  const SceneSpec s = scene("paper-plane");
  SuggestOptions exact;
  exact.verify = false;
  SuggestOptions over = exact;
  over.max_factor_flops = 1;
  const DampingSuggestion e = suggest_damping(s, s.params, s.rules, exact);
  const DampingSuggestion d = suggest_damping(s, s.params, s.rules, over);
  EXPECT_FALSE(e.proved_only);
  ASSERT_TRUE(d.proved_only);
  EXPECT_FALSE(d.exact.computed());
  EXPECT_EQ(d.gamma_min, e.gamma_min);
  EXPECT_LT(d.gamma_max, e.gamma_max);                       // 0.039775 < 0.039805
  EXPECT_NEAR(d.gamma_max, d.safe_max, 1e-11 * d.safe_max);  // SPEC 9's bound, inward
  EXPECT_GE(d.gamma_unstable_from, e.gamma_max);             // the bracket holds the limit
  EXPECT_LT(d.gamma_unstable_from, 1.001 * e.gamma_max);
  for (int k = 0; k <= 8; ++k) {
    Params p = s.params;
    p.gamma = d.gamma_min + (d.gamma_max - d.gamma_min) * k / 8;
    const Model m = compile_model(s.model, p);
    EXPECT_TRUE(exact_stability(m, m.spec().rest, p).stable) << p.gamma;
  }
  // The best gamma minimises a bound over [SPEC 9's floor, Gershgorin's bound] = [1, 9] kappa/m,
  // which holds the exact spectrum [1, 7.81]: its radius bound is no lower than the exact one.
  ASSERT_TRUE(std::isfinite(d.gamma_best));
  EXPECT_GE(d.gamma_best, d.gamma_min);
  EXPECT_LE(d.gamma_best, d.gamma_max);
  // (both lower ends bound lambda_min = 1 from below, the floor 1e-12 more tightly)
  EXPECT_GE(d.best_rho, e.best_rho - 1e-9);
  EXPECT_LT(d.best_rho, 1);

  Params g = s.params;  // gamma = 0.002
  const StepSuggestion te = suggest_step(s, g, s.rules, exact);
  const StepSuggestion t = suggest_step(s, g, s.rules, over);
  ASSERT_TRUE(t.proved_only);
  EXPECT_LE(t.dt_exact, te.dt_exact);  // 0.4805 <= 0.50396
  EXPECT_GE(t.dt_unstable_from, te.dt_exact);
  EXPECT_LT(t.dt_unstable_from, 1.001 * te.dt_exact);
  EXPECT_EQ(t.dt_all, te.dt_all);  // Delingette's 1/pi is the most cautious either way

  // Implicit Euler with K >= 0 proved (SPEC 9's floor): every gamma and dt.
  g.integrator = Integrator::implicit_euler;
  const DampingSuggestion di = suggest_damping(s, g, s.rules, over);
  EXPECT_TRUE(di.proved_only);
  EXPECT_TRUE(std::isinf(di.gamma_max));
  EXPECT_TRUE(std::isinf(suggest_step(s, g, s.rules, over).dt_exact));
}

// With every spring compressed at rest SPEC 9's floor proves nothing, so over the budget
// nothing is proved stable and nothing suggested: an error that says so.
TEST(Suggest, OverTheBudgetWithNothingProvedItSaysSo) {
  SceneSpec s = scene("paper-plane");
  for (Spring& sp : s.model.springs) sp.rest_length *= 1.05;
  SuggestOptions over;
  over.verify = false;
  over.max_factor_flops = 1;
  try {
    suggest_damping(s, s.params, s.rules, over);
    ADD_FAILURE() << "suggested without a proof";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a damping range proved stable without them"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace dampbound
