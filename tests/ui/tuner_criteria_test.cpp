// The tuner's criteria and suggestions (ui/tuner_criteria.hpp) without a window: live
// criteria, the cached exact analysis, the background suggestion and applying it.
#include "ui/tuner_criteria.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "core/analysis/damping_limits.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/run/scene.hpp"
#include "tests/test_scenes.hpp"
#include "ui/tuner.hpp"

namespace dampbound::ui {
namespace {

SceneSpec plane(int n) {
  SceneSpec s = paper_plane_scene(n);
  s.name = "plane";
  s.rules.max_iterations = 300;
  return s;
}

SceneSpec loaded_chain() {
  SceneSpec chain;
  chain.name = "chain";
  chain.model = test::loaded_chain();
  return chain;
}

const CriterionResult* find(const std::vector<CriterionResult>& rows, const std::string& name) {
  for (const auto& r : rows)
    if (r.name.find(name) != std::string::npos) return &r;
  return nullptr;
}

TEST(TunerCriteria, LiveCriteriaWithACachedExactAnalysis) {
  Tuner t(plane(8));
  t.criteria_state().set_slow_threshold(1e9);  // counts analyses: no throttle, however slow
  const auto& at_rest = t.criteria();
  ASSERT_FALSE(at_rest.empty());
  const CriterionResult* lower = find(at_rest, "paper lower bound");
  ASSERT_NE(lower, nullptr);
  EXPECT_EQ(lower->verdict, CriterionVerdict::within);  // gamma = 2 sqrt(m kappa)
  ASSERT_NE(find(at_rest, "exact"), nullptr);
  const int runs = t.criteria_state().exact_runs();
  t.step(3);
  const auto& moving = t.criteria();
  EXPECT_EQ(t.criteria_state().exact_runs(), runs);  // same parameters: cached
  const CriterionResult* upper = find(moving, "paper upper bound");
  ASSERT_NE(upper, nullptr);
  EXPECT_NE(upper->verdict, CriterionVerdict::not_applicable);  // nodes move now
  Params p = t.params();
  p.gamma = 0.0005;
  ASSERT_TRUE(t.set_params(p));
  const int reused = t.criteria_state().spectra_reused();
  const auto& below = t.criteria();
  EXPECT_EQ(t.criteria_state().exact_runs(), runs + 1);
  EXPECT_EQ(t.criteria_state().spectra_reused(), reused + 1);  // gamma: A's spectrum as it was
  EXPECT_EQ(find(below, "paper lower bound")->verdict, CriterionVerdict::beyond);
  t.cut({0, 1, 2});
  t.criteria();
  EXPECT_EQ(t.criteria_state().exact_runs(), runs + 2);  // springs changed
  EXPECT_EQ(t.criteria_state().spectra_reused(), reused + 1);  // another A: certified anew
}

TEST(TunerCriteria, ALargeMeshRefreshesItsRowsAtTheFollowInterval) {
  Tuner t(plane(8));
  TunerCriteria& c = t.criteria_state();
  c.set_worker_nodes(0);  // this plane counts as large
  c.set_slow_threshold(1e9);
  c.set_follow_interval(1e9);
  t.criteria();
  c.wait();  // the analysis at rest arrives: the rows are evaluated again with it
  EXPECT_EQ(find(t.criteria(), "paper upper bound")->verdict, CriterionVerdict::not_applicable);
  EXPECT_EQ(c.rows_iteration(), 0);
  t.step(3);
  // Only the state moved, within the interval: the rows on show are the last ones, and say so.
  EXPECT_EQ(find(t.criteria(), "paper upper bound")->verdict, CriterionVerdict::not_applicable);
  EXPECT_EQ(c.rows_iteration(), 0);
  Params p = t.params();
  p.gamma = 0.0005;
  ASSERT_TRUE(t.set_params(p));  // a parameter: at once
  EXPECT_EQ(find(t.criteria(), "paper lower bound")->verdict, CriterionVerdict::beyond);
  c.set_follow_interval(0);
  t.step(1);
  EXPECT_NE(find(t.criteria(), "paper upper bound")->verdict, CriterionVerdict::not_applicable);
  EXPECT_EQ(c.rows_iteration(), 4);
  c.wait();
}

TEST(TunerCriteria, ExactAnalysisCanFollowTheState) {
  Tuner t(plane(8));
  TunerCriteria& c = t.criteria_state();
  EXPECT_FALSE(c.at_current_state());
  const ExactStability* rest = t.exact();
  ASSERT_NE(rest, nullptr);
  const double lambda_rest = rest->spectrum.lambda_max;
  t.step(5);
  ASSERT_NE(t.exact(), nullptr);
  EXPECT_EQ(t.exact()->spectrum.lambda_max, lambda_rest);  // at rest: cached
  EXPECT_TRUE(c.exact_at_rest());
  // At the current state the 5 cm perturbation stretches the springs around the watched
  // node: the tangent stiffness, and so lambda_max, differ from the rest state's. The
  // analysis runs on a worker thread; until it is done the last result stays on show.
  c.set_at_current_state(true);
  c.set_follow_interval(1e9);  // never twice: the throttle, without a clock in the test
  const int runs = c.exact_runs();
  ASSERT_NE(t.exact(), nullptr);
  EXPECT_EQ(c.exact_runs(), runs + 1);
  c.wait();
  const ExactStability* now = t.exact();
  ASSERT_NE(now, nullptr);
  EXPECT_FALSE(c.exact_at_rest());
  EXPECT_EQ(c.exact_iteration(), 5);
  EXPECT_NE(now->spectrum.lambda_max, lambda_rest);
  // The same state again: cached; a later state within the interval: throttled (kept).
  t.exact();
  EXPECT_EQ(c.exact_runs(), runs + 1);
  t.step(1);
  t.exact();
  c.wait();
  EXPECT_EQ(c.exact_runs(), runs + 1);
  EXPECT_EQ(c.exact_iteration(), 5);
  c.set_follow_interval(0.05);  // once the interval (and 4 analysis durations) are over, a
  t.step(1);                    // new state is analysed
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  t.exact();
  c.wait();
  EXPECT_EQ(c.exact_runs(), runs + 2);
  EXPECT_EQ(c.exact_iteration(), 7);
  // Back at rest: recomputed at once, the rest value again.
  c.set_at_current_state(false);
  ASSERT_NE(t.exact(), nullptr);
  EXPECT_EQ(c.exact_runs(), runs + 3);
  EXPECT_EQ(t.exact()->spectrum.lambda_max, lambda_rest);
  EXPECT_TRUE(c.exact_at_rest());
}

TEST(TunerCriteria, LargeMeshesAreAnalysedAtRestOnTheWorker) {
  // Above the worker threshold (here 0 nodes, as for a 40k-node mesh) no frame waits for the
  // analysis at rest: the first call has no result yet and says it is computing; a parameter
  // change keeps the last result on show until the new one arrives.
  Tuner t(plane(8));
  TunerCriteria& c = t.criteria_state();
  c.set_worker_nodes(0);
  c.set_slow_threshold(1e9);  // no throttle, however slow the build (ASan): every change recomputes
  EXPECT_EQ(t.exact(), nullptr);
  EXPECT_TRUE(c.computing());
  c.wait();
  EXPECT_FALSE(c.computing());
  const ExactStability* first = t.exact();
  ASSERT_NE(first, nullptr);
  EXPECT_TRUE(c.exact_at_rest());
  const double gamma_hi = first->gamma_hi;
  Params p = t.params();
  p.dt *= 0.5;
  ASSERT_TRUE(t.set_params(p));
  const ExactStability* meanwhile = t.exact();
  ASSERT_NE(meanwhile, nullptr);
  EXPECT_EQ(meanwhile->gamma_hi, gamma_hi);  // the last result, while the new one computes
  EXPECT_TRUE(c.computing());
  c.wait();
  ASSERT_NE(t.exact(), nullptr);
  EXPECT_GT(t.exact()->gamma_hi, gamma_hi);  // a smaller dt allows more damping (SPEC 7)
}

// The worker's progress (what it does, its seconds) and Cancel: a cancelled analysis is not
// started again for the same parameters, and the next change starts one.
// The window's frame waits for the analysis at most set_frame_wait (kCriteriaFrameWait), on
// every mesh: it used to run in the frame below 5000 free nodes (1.3 s on stiff-region's first
// frame). With no wait at all the frame returns at once, the analysis on its way; the next
// frame after it finished shows it.
TEST(TunerCriteria, NoFrameWaitsForTheAnalysisLongerThanTheFrameWait) {
  Tuner t(plane(8));
  TunerCriteria& c = t.criteria_state();
  c.set_frame_wait(0);
  t.criteria();
  EXPECT_TRUE(c.computing());
  EXPECT_EQ(t.criteria_state().exact(t.session(), t.topology(), t.state_version()), nullptr);
  c.wait();
  EXPECT_FALSE(c.computing());
  EXPECT_NE(c.exact(t.session(), t.topology(), t.state_version()), nullptr);
  // A parameter change: again on the worker, the frame not held.
  Params p = t.params();
  p.gamma = 0.0005;
  ASSERT_TRUE(t.set_params(p));
  t.criteria();
  EXPECT_TRUE(c.computing());
  c.wait();
  ASSERT_NE(c.exact(t.session(), t.topology(), t.state_version()), nullptr);
  EXPECT_FALSE(c.computing());
  // The default (tests, scripted runs): the frame shows its own parameters' analysis.
  Tuner u(plane(8));
  u.criteria();
  EXPECT_FALSE(u.criteria_state().computing());
  EXPECT_NE(u.criteria_state().exact(u.session(), u.topology(), u.state_version()), nullptr);
}

TEST(TunerCriteria, TheWorkerSaysWhatItDoesAndCancelStopsIt) {
  Tuner t(plane(8));
  TunerCriteria& c = t.criteria_state();
  c.set_slow_threshold(1e9);
  Params p = t.params();
  p.rayleigh_mass = 0.1;  // SPEC 10's general damping: always on the worker
  ASSERT_TRUE(t.set_params(p));
  EXPECT_EQ(t.exact(), nullptr);
  ASSERT_TRUE(c.computing());
  EXPECT_NE(c.computing_stage().find("general damping matrix's limits"), std::string::npos)
      << c.computing_stage();
  EXPECT_NE(c.computing_stage().find("at rest on 64 free nodes"), std::string::npos)
      << c.computing_stage();
  EXPECT_GE(c.computing_seconds(), 0.0);
  const int runs = c.exact_runs();
  c.cancel();
  EXPECT_FALSE(c.computing());
  EXPECT_TRUE(c.cancelled());
  EXPECT_EQ(t.exact(), nullptr);
  EXPECT_FALSE(c.computing()) << "started again for the same parameters";
  EXPECT_EQ(c.exact_runs(), runs);
  p.rayleigh_mass = 0.2;
  ASSERT_TRUE(t.set_params(p));
  t.exact();
  EXPECT_TRUE(c.computing());
  EXPECT_FALSE(c.cancelled());
  c.wait();
  ASSERT_NE(t.exact(), nullptr);
  EXPECT_GT(c.last_seconds(), 0.0);
}

TEST(TunerCriteria, TheFactorisationBudgetReachesTheAnalysis) {
  // 14 x 14 nodes: 588 rows, above the dense route's 400, so the analysis factorises.
  Tuner t(plane(14));
  TunerCriteria& c = t.criteria_state();
  EXPECT_EQ(c.factor_budget(), kDefaultFactorBudget);
  const ExactStability* within = t.exact();
  ASSERT_NE(within, nullptr);
  EXPECT_EQ(within->method, ExactMethod::per_mode);
  const double gamma_hi = within->gamma_hi, dt_max = within->dt_max;  // it is replaced below
  const int runs = c.exact_runs();
  c.set_factor_budget(1.0);  // one flop: no factorisation fits
  const ExactStability* over = t.exact();
  ASSERT_NE(over, nullptr);
  EXPECT_EQ(c.exact_runs(), runs + 1);  // a new budget is analysed anew
  EXPECT_EQ(over->method, ExactMethod::over_budget);
  EXPECT_EQ(over->factor_budget, 1.0);
  EXPECT_TRUE(std::isnan(over->gamma_hi));
  EXPECT_EQ(c.shown(), over);
  c.set_factor_budget(1.0);  // the same budget: cached
  t.exact();
  EXPECT_EQ(c.exact_runs(), runs + 1);

  // Suggest over the budget: what is proved stable without a factorisation (SPEC 9's
  // Gershgorin proof), inside the exact range.
  TunerSuggest s;
  s.set_factor_budget(1.0);
  s.start(t.session());
  s.wait();
  ASSERT_TRUE(s.result().has_value()) << s.error();
  EXPECT_TRUE(s.error().empty());
  const DampingSuggestion& d = s.result()->damping;
  EXPECT_TRUE(d.proved_only);
  EXPECT_LT(d.gamma_max, gamma_hi);
  EXPECT_GE(d.gamma_unstable_from, gamma_hi);
  EXPECT_TRUE(s.result()->step.proved_only);
  EXPECT_LT(s.result()->step.dt_exact, dt_max);
}

// A scene whose rest state is not an equilibrium (a slack chain pulled down): the panel's
// note. The paper plane's rest state is one.
TEST(TunerCriteria, SaysWhenTheRestStateIsNotAnEquilibrium) {
  Tuner t(loaded_chain());
  ASSERT_NE(t.exact(), nullptr);
  const NetForce* n = t.criteria_state().rest_net_force();
  ASSERT_NE(n, nullptr);
  EXPECT_FALSE(n->balanced());
  EXPECT_DOUBLE_EQ(n->largest, 0.0005);
  Tuner flat(plane(6));
  ASSERT_NE(flat.exact(), nullptr);
  ASSERT_NE(flat.criteria_state().rest_net_force(), nullptr);
  EXPECT_TRUE(flat.criteria_state().rest_net_force()->balanced());
}

// A chain sagging under loads: at the static equilibrium its tension gives it sideways
// stiffness, so the analysis there differs from the one at rest, and is the one that
// `bounds --equilibrium` prints (exact_stability at static_equilibrium's positions).
TEST(TunerCriteria, AnalysesAtTheStaticEquilibrium) {
  Tuner t(loaded_chain());
  TunerCriteria& c = t.criteria_state();
  const ExactStability* rest = t.exact();
  ASSERT_NE(rest, nullptr);
  const double lambda_rest = rest->spectrum.lambda_max;
  c.set_linearisation(Linearisation::equilibrium);
  EXPECT_FALSE(c.at_current_state());
  const int runs = c.exact_runs();
  t.exact();  // on the worker thread, Newton first
  EXPECT_EQ(c.exact_runs(), runs + 1);
  c.wait();
  const ExactStability* held = t.exact();
  ASSERT_NE(held, nullptr);
  EXPECT_FALSE(c.exact_at_rest());
  EXPECT_EQ(c.rest_net_force(), nullptr);  // the note belongs to the analysis at rest
  EXPECT_TRUE(c.equilibrium_failure().empty());
  const Equilibrium* e = c.exact_equilibrium();
  ASSERT_NE(e, nullptr);
  EXPECT_TRUE(e->converged);
  EXPECT_GT(e->iterations, 0);
  EXPECT_TRUE(e->net.balanced());
  const Model& model = t.session().model();
  const ExactStability want =
      exact_stability(model, static_equilibrium(model).x, t.session().params());
  EXPECT_EQ(held->spectrum.lambda_max, want.spectrum.lambda_max);
  EXPECT_EQ(held->gamma_hi, want.gamma_hi);
  EXPECT_EQ(held->dt_max, want.dt_max);
  EXPECT_LT(held->spectrum.lambda_max, lambda_rest - 0.1);  // 3.7151536 against 3.9189859
  // Cached: the run moving does not start another; back at rest the rest value again.
  t.step(5);
  t.exact();
  EXPECT_EQ(c.exact_runs(), runs + 1);
  c.set_linearisation(Linearisation::rest);
  ASSERT_NE(t.exact(), nullptr);
  EXPECT_EQ(t.exact()->spectrum.lambda_max, lambda_rest);
  EXPECT_TRUE(c.exact_at_rest());
  EXPECT_EQ(c.exact_equilibrium(), nullptr);
}

// Where the tuner leaves the exact analysis out by design, it says why (the Criteria tab shows
// "exact analysis unavailable: ..."), and nothing where it computes it.
TEST(TunerCriteria, SaysWhyItDoesNotComputeTheExactAnalysis) {
  const SceneSpec small = paper_plane_scene(8), big = paper_plane_scene(230);
  Params p = small.params;
  EXPECT_EQ(exact_not_computed_reason(compile_model(small.model, p), p), "");
  EXPECT_EQ(exact_not_computed_reason(compile_model(big.model, p), p), "");  // nodal only
  p.kd = 0.002;
  EXPECT_EQ(exact_not_computed_reason(compile_model(small.model, p), p), "");
  const std::string many = exact_not_computed_reason(compile_model(big.model, p), p);
  EXPECT_NE(many.find("on 52900 free nodes (over 50000)"), std::string::npos) << many;
  EXPECT_NE(many.find("dampbound bounds"), std::string::npos) << many;
  p.integrator = Integrator::rk4;
  const std::string other = exact_not_computed_reason(compile_model(small.model, p), p);
  EXPECT_NE(other.find("paper's semi-implicit step only"), std::string::npos) << other;
}

TEST(TunerCriteria, LinearisationNamesRoundTrip) {
  for (Linearisation at : {Linearisation::rest, Linearisation::state, Linearisation::equilibrium})
    EXPECT_EQ(parse_linearisation(to_string(at)), at);
  EXPECT_FALSE(parse_linearisation("Rest").has_value());
  EXPECT_FALSE(parse_linearisation("").has_value());
}

// Newton's method needs factorisations: over the budget there is no equilibrium to analyse
// at, and the criteria say why instead of showing the rest state's analysis as if it were.
TEST(TunerCriteria, SaysWhyThereIsNoAnalysisAtTheEquilibrium) {
  Tuner t(loaded_chain());
  TunerCriteria& c = t.criteria_state();
  c.set_factor_budget(1);  // one flop
  c.set_linearisation(Linearisation::equilibrium);
  t.exact();
  c.wait();
  EXPECT_EQ(t.exact(), nullptr);
  EXPECT_EQ(c.exact_equilibrium(), nullptr);
  EXPECT_NE(c.equilibrium_failure().find("needs factorisations"), std::string::npos)
      << c.equilibrium_failure();
  c.set_factor_budget(kDefaultFactorBudget);
  t.exact();
  c.wait();
  ASSERT_NE(t.exact(), nullptr);
  EXPECT_TRUE(c.equilibrium_failure().empty());
  ASSERT_NE(c.exact_equilibrium(), nullptr);
  // A loaded node with no spring: the energy falls without end, Newton's method stops after
  // its 200 steps, and there is nothing to analyse.
  SceneSpec loose;
  loose.name = "loose";
  add_node(loose.model, Vec3(0, 0, 0));
  add_node(loose.model, Vec3(0.5, 0, 0));
  add_node(loose.model, Vec3(2, 0, 0));
  add_spring(loose.model, 0, 1);
  loose.model.fixed[0] = 1;
  loose.model.external_force[2] = Vec3(0, -0.0005, 0);
  Tuner u(loose);
  TunerCriteria& d = u.criteria_state();
  d.set_linearisation(Linearisation::equilibrium);
  u.exact();
  d.wait();
  EXPECT_EQ(u.exact(), nullptr);
  EXPECT_EQ(d.exact_equilibrium(), nullptr);
  EXPECT_NE(d.equilibrium_failure().find("no static equilibrium found in 200 Newton steps"),
            std::string::npos)
      << d.equilibrium_failure();
}

TEST(TunerCriteria, ExactGammaMaxIsTheIntegratorsLimit) {
  Tuner t(plane(6));
  const auto g = t.exact_gamma_max();
  ASSERT_TRUE(g.has_value());
  const ExactStability* e = t.criteria_state().exact(t.session(), t.topology());
  ASSERT_NE(e, nullptr);
  EXPECT_DOUBLE_EQ(*g, e->gamma_hi);
  // Semi-implicit Euler, uniform rate: gamma < 2m/dt - m lambda_max dt / 2 (SPEC 7).
  const Params& p = t.params();
  EXPECT_NEAR(*g, 2 * p.m / p.dt - p.m * e->spectrum.lambda_max * p.dt / 2, 1e-9);
  Params q = p;
  q.integrator = Integrator::implicit_euler;  // unconditionally stable: no finite limit
  ASSERT_TRUE(t.set_params(q));
  EXPECT_FALSE(t.exact_gamma_max().has_value());
}

TEST(TunerSuggest, RunsInTheBackgroundAndCanBeApplied) {
  Tuner t(plane(8));
  Params p = t.params();
  p.gamma = 0.0003;
  ASSERT_TRUE(t.set_params(p));
  TunerSuggest s;
  EXPECT_FALSE(s.poll());
  s.start(t.scene(), t.params(), t.session().rules());
  s.wait();
  ASSERT_TRUE(s.result().has_value()) << s.error();
  EXPECT_FALSE(s.busy());
  const Suggestion& r = *s.result();
  EXPECT_DOUBLE_EQ(r.params.gamma, 0.0003);
  EXPECT_FALSE(r.damping.empty);
  EXPECT_NEAR(r.damping.gamma_min, lower_bound(p.m, p.kappa), 1e-12);
  EXPECT_GE(r.damping.gamma_best, r.damping.gamma_min);
  EXPECT_LT(r.damping.gamma_best, r.damping.gamma_max);
  EXPECT_FALSE(r.damping.runs.empty());
  EXPECT_GT(r.step.dt_all, 0.0);
  ASSERT_TRUE(t.set_params(with_best_gamma(t.params(), r)));
  EXPECT_DOUBLE_EQ(t.params().gamma, r.damping.gamma_best);
  ASSERT_TRUE(t.set_params(with_suggested_dt(t.params(), r)));
  EXPECT_DOUBLE_EQ(t.params().dt, r.step.dt_all);
}

TEST(TunerSuggest, IsForTheMeshAsCut) {
  Tuner t(plane(8));
  TunerSuggest whole;
  whole.start(t.session());
  whole.wait();
  ASSERT_TRUE(whole.result().has_value()) << whole.error();
  EXPECT_EQ(whole.result()->springs, t.session().model().spec().spring_count());
  EXPECT_EQ(whole.result()->springs_cut, 0);
  // Cut every spring of the node in the middle of the grid: the suggestion is computed (and
  // its runs verified) on the mesh without them.
  std::vector<int> around;
  const Model& m = t.session().model();
  for (int k = 0; k < m.spec().spring_count(); ++k) {
    const Spring& sp = m.spec().springs[static_cast<size_t>(k)];
    if (sp.i == t.session().watched() || sp.j == t.session().watched()) around.push_back(k);
  }
  ASSERT_EQ(t.cut(around), 6);
  TunerSuggest cut;
  cut.start(t.session());
  cut.wait();
  ASSERT_TRUE(cut.result().has_value()) << cut.error();
  EXPECT_EQ(cut.result()->springs, whole.result()->springs - 6);
  EXPECT_EQ(cut.result()->springs_cut, 6);
  // The perturbed node now hangs on its anchor alone: its runs differ from the whole mesh's.
  ASSERT_FALSE(cut.result()->damping.runs.empty());
  ASSERT_FALSE(whole.result()->damping.runs.empty());
  const RunResult& a = cut.result()->damping.runs.front().result;
  const RunResult& b = whole.result()->damping.runs.front().result;
  EXPECT_TRUE(a.iterations != b.iterations || a.max_displacement != b.max_displacement);
}

}  // namespace
}  // namespace dampbound::ui

namespace dampbound::ui {
namespace {

// SPEC 10 in the tuner: the exact limit follows kd, alpha and beta as they are set (the
// limits of the general damping matrix, on the worker), and goes back when they are off.
TEST(TunerCriteriaOtherDamping, TheExactLimitFollowsDashpotsAndRayleighDamping) {
  SceneSpec scene = paper_plane_scene(8);
  Tuner t(scene);
  t.criteria_state().set_slow_threshold(1e9);  // no throttling: each change is analysed
  auto exact_now = [&t] {
    t.exact_gamma_max();
    t.criteria_state().wait();
    return t.exact_gamma_max();
  };
  const std::optional<double> nodal = exact_now();
  ASSERT_TRUE(nodal.has_value());
  for (const auto& set : {+[](Params& p) { p.kd = 0.002; },
                          +[](Params& p) { p.rayleigh_mass = 0.5; },
                          +[](Params& p) { p.rayleigh_stiffness = 0.01; }}) {
    Params p = t.params();
    set(p);
    ASSERT_TRUE(t.set_params(p));
    const std::optional<double> got = exact_now();
    const Model& m = t.session().model();
    const GeneralLimits want = general_limits(m, m.spec().rest, p);
    ASSERT_TRUE(got.has_value());
    EXPECT_EQ(*got, want.gamma_max);
    EXPECT_LT(*got, *nodal);  // more damping elsewhere leaves less room for gamma
    p.kd = p.rayleigh_mass = p.rayleigh_stiffness = 0;
    ASSERT_TRUE(t.set_params(p));
    EXPECT_EQ(exact_now(), nodal);
  }
}

}  // namespace
}  // namespace dampbound::ui
