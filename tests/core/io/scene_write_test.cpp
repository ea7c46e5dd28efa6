// Scenes written back as TOML: every shipped scene reads back the same, and the save-and-check
// round trip (measured runs -> [[expect]] -> check passes; an edited parameter -> it fails).
#include "core/io/scene_write.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <utility>

#include "core/analysis/expect.hpp"
#include "core/io/scene_file.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

namespace fs = std::filesystem;

void expect_same_params(const Params& a, const Params& b) {
  EXPECT_EQ(a.m, b.m);
  EXPECT_EQ(a.kappa, b.kappa);
  EXPECT_EQ(a.gamma, b.gamma);
  EXPECT_EQ(a.dt, b.dt);
  EXPECT_EQ(a.factor, b.factor);
  EXPECT_EQ(a.policy, b.policy);
  EXPECT_EQ(a.integrator, b.integrator);
}

void expect_same_scene(const SceneSpec& a, const SceneSpec& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  EXPECT_TRUE(same_topology(a.model, b.model));
  expect_same_params(a.params, b.params);
  EXPECT_EQ(a.watched, b.watched);
  ASSERT_EQ(a.perturbations.size(), b.perturbations.size());
  for (size_t k = 0; k < a.perturbations.size(); ++k) {
    EXPECT_EQ(a.perturbations[k].node, b.perturbations[k].node);
    EXPECT_EQ(a.perturbations[k].displacement, b.perturbations[k].displacement);
    EXPECT_EQ(a.perturbations[k].velocity, b.perturbations[k].velocity);
  }
  EXPECT_EQ(a.rules.max_iterations, b.rules.max_iterations);
  EXPECT_EQ(a.rules.restore_fraction, b.rules.restore_fraction);
  EXPECT_EQ(a.rules.diverge_factor, b.rules.diverge_factor);
  EXPECT_EQ(a.rules.reference, b.rules.reference);
  ASSERT_EQ(a.cuts.size(), b.cuts.size());
  for (size_t k = 0; k < a.cuts.size(); ++k) {
    EXPECT_EQ(a.cuts[k].iteration, b.cuts[k].iteration);
    EXPECT_EQ(a.cuts[k].from[0], b.cuts[k].from[0]);
    EXPECT_EQ(a.cuts[k].to[1], b.cuts[k].to[1]);
  }
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (size_t k = 0; k < a.runs.size(); ++k) {
    EXPECT_EQ(a.runs[k].label, b.runs[k].label);
    expect_same_params(a.runs[k].params, b.runs[k].params);
    EXPECT_EQ(a.runs[k].rules.max_iterations, b.runs[k].rules.max_iterations);
  }
  ASSERT_EQ(a.expectations.size(), b.expectations.size());
  for (size_t k = 0; k < a.expectations.size(); ++k) {
    const Expectation &x = a.expectations[k], &y = b.expectations[k];
    EXPECT_EQ(x.run, y.run);
    EXPECT_EQ(x.rule, y.rule);
    EXPECT_EQ(x.outcome, y.outcome);
    EXPECT_EQ(x.iterations_min, y.iterations_min);
    EXPECT_EQ(x.iterations_max, y.iterations_max);
    EXPECT_EQ(x.first_entry_min, y.first_entry_min);
    EXPECT_EQ(x.first_entry_max, y.first_entry_max);
    EXPECT_EQ(x.left, y.left);
    EXPECT_EQ(x.left_at_min, y.left_at_min);
    EXPECT_EQ(x.left_at_max, y.left_at_max);
    EXPECT_EQ(x.settled_at_min, y.settled_at_min);
    EXPECT_EQ(x.settled_at_max, y.settled_at_max);
    EXPECT_EQ(x.max_displacement_below, y.max_displacement_below);
    EXPECT_EQ(x.unstabilisable_max, y.unstabilisable_max);
    EXPECT_EQ(x.violations_max, y.violations_max);
    EXPECT_EQ(x.violations_min, y.violations_min);
  }
}

std::string temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("dampbound_scene_write_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

TEST(SceneWrite, EveryShippedSceneReadsBackTheSame) {
  const std::string dir = temp_dir("shipped");
  int scenes = 0;
  for (const auto& e : fs::directory_iterator(test::source_path("scenes"))) {
    if (e.path().extension() != ".toml") continue;
    SCOPED_TRACE(e.path().string());
    const SceneSpec s = load_scene(e.path().string());
    const std::string dest = dir + "/" + e.path().filename().string();
    const std::string text = scene_toml(s, dest, {"a header line"});
    EXPECT_EQ(text.rfind("# a header line\n", 0), 0u);
    { std::ofstream(dest) << text; }
    expect_same_scene(s, load_scene(dest));
    ++scenes;
  }
  EXPECT_GE(scenes, 8);
}

TEST(SceneWrite, ExplicitGeometryWhenThereIsNoSourceFile) {
  SceneSpec s = load_scene(test::source_path("scenes/two-node-damping.toml"));
  s.path.clear();  // as if built in code: nodes and springs are written out
  const std::string text = scene_toml(s, "/tmp/x.toml");
  EXPECT_NE(text.find("[[node]]"), std::string::npos);
  expect_same_scene(s, parse_scene(text, "/tmp/x.toml"));
  // A grid with regions and no source file is written node by node, and still the same.
  SceneSpec stiff = load_scene(test::source_path("scenes/stiff-region.toml"));
  stiff.path.clear();
  expect_same_scene(stiff, parse_scene(scene_toml(stiff, "/tmp/y.toml"), "/tmp/y.toml"));
}

TEST(SceneWrite, MeshPathFollowsTheNewFile) {
  const std::string dir = temp_dir("mesh");
  const SceneSpec s = load_scene(test::source_path("scenes/tissue-cap.toml"));
  const std::string dest = dir + "/sub/cap.toml";
  fs::create_directories(dir + "/sub");
  { std::ofstream(dest) << scene_toml(s, dest); }
  const SceneSpec back = load_scene(dest);
  EXPECT_TRUE(same_topology(s.model, back.model));
}

TEST(SceneWrite, ExpectationOfAMeasuredRun) {
  RunResult r;
  r.outcome = Outcome::restored;
  r.iterations = 112;
  r.max_displacement = 0.04;
  r.violations = 7;
  ExpectTolerance tol;
  tol.iterations = 3;
  tol.iteration_fraction = 0;
  tol.displacement_factor = 2;
  tol.counts = true;
  const Expectation e = expectation_for(r, "pin", tol);
  EXPECT_EQ(e.run, "pin");
  EXPECT_EQ(e.outcome, Outcome::restored);
  EXPECT_EQ(*e.iterations_min, 109);
  EXPECT_EQ(*e.iterations_max, 115);
  EXPECT_DOUBLE_EQ(*e.max_displacement_below, 0.08);
  EXPECT_EQ(*e.violations_max, 7);
  EXPECT_EQ(*e.unstabilisable_max, 0);
  r.outcome = Outcome::diverged;
  const Expectation d = expectation_for(r, "", default_expect_tolerance());
  EXPECT_FALSE(d.max_displacement_below);  // a diverged run's displacement says nothing
  r.outcome = Outcome::not_restored;
  r.iterations = 1000;
  EXPECT_FALSE(expectation_for(r, "", default_expect_tolerance()).iterations_min);
  // The settled rule (SPEC 8): entered at 40, left at 55, settled from 90 to the limit.
  r.outcome = Outcome::settled;
  r.first_entry = 40;
  r.left_at = 55;
  r.settled_at = 90;
  const Expectation s = expectation_for(r, "pin", tol, StopRule::settled);
  EXPECT_EQ(s.rule, StopRule::settled);
  EXPECT_FALSE(s.iterations_min);  // the limit
  EXPECT_EQ(*s.first_entry_min, 37);
  EXPECT_EQ(*s.first_entry_max, 43);
  EXPECT_TRUE(*s.left);
  EXPECT_EQ(*s.left_at_min, 52);
  EXPECT_EQ(*s.settled_at_max, 93);
  // Written and read back, under the settled rule's keys.
  SceneSpec scene = load_scene(test::source_path("scenes/two-node.toml"));
  scene.runs = {{"pin", scene.params, scene.rules}};
  scene.expectations = {s};
  expect_same_scene(scene, parse_scene(scene_toml(scene, "/tmp/s.toml"), "/tmp/s.toml"));
}

// The default tolerance grows with the iteration: +-2 early, +-5 % later.
TEST(SceneWrite, IterationToleranceIsRelative) {
  RunResult r;
  r.outcome = Outcome::restored;
  r.iterations = 20;
  const Expectation early = expectation_for(r, "", default_expect_tolerance());
  EXPECT_EQ(*early.iterations_min, 18);
  EXPECT_EQ(*early.iterations_max, 22);
  r.iterations = 110;
  const Expectation late = expectation_for(r, "", default_expect_tolerance());
  EXPECT_EQ(*late.iterations_min, 104);
  EXPECT_EQ(*late.iterations_max, 116);  // 114, what FMA contraction measured, is inside
  EXPECT_FALSE(late.max_displacement_below);
}

// Saved checks travel: a run whose dt moves by one ulp (which changes the rounding of every
// step, as another compiler's would) still passes the expectations saved from the original,
// under both rules.
TEST(SceneWrite, SavedChecksSurviveAnUlp) {
  for (StopRule rule : {StopRule::first_entry, StopRule::settled}) {
    SceneSpec s = load_scene(test::source_path("scenes/paper-plane.toml"));
    s.rules.rule = rule;
    s.expectations = {
        expectation_for(run_labelled(s, "", rule), "", default_expect_tolerance(), rule)};
    s.params.dt = std::nextafter(s.params.dt, 1.0);
    for (const auto& r : check_expectations(s))
      EXPECT_TRUE(r.pass) << to_string(rule) << ": " << r.what << " measured " << r.measured;
  }
}

// The tuner's "Save as scene" without a window: two runs measured, written with their
// expectations, read back and checked; then one parameter edited in the file, and it fails.
TEST(SceneWrite, SavedRunsPassCheckAndAnEditFails) {
  SceneSpec s = load_scene(test::source_path("scenes/paper-plane.toml"));
  s.params.gamma = 0.002;
  for (const auto& [label, gamma] : {std::pair<const char*, double>{"under", 0.0005},
                                     std::pair<const char*, double>{"at", 0.002}}) {
    RunSpec run{label, s.params, s.rules};
    run.params.gamma = gamma;
    s.runs.push_back(run);
  }
  for (const RunSpec& run : s.runs)
    s.expectations.push_back(
        expectation_for(run_labelled(s, run.label), run.label, default_expect_tolerance()));
  const std::string dir = temp_dir("check");
  const std::string dest = dir + "/tuned.toml";
  std::string text = scene_toml(s, dest);
  { std::ofstream(dest) << text; }
  const SceneSpec back = load_scene(dest);
  const auto results = check_expectations(back);
  ASSERT_EQ(results.size(), 4u);  // outcome and iterations per run
  for (const auto& r : results) EXPECT_TRUE(r.pass) << r.what << ": " << r.measured;
  // Edit the first run's gamma in the file: its iteration moves out of the tolerance.
  const std::string from = "gamma = 0.0005";
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(), "gamma = 0.0008");
  { std::ofstream(dest) << text; }
  int failed = 0;
  for (const auto& r : check_expectations(load_scene(dest))) failed += !r.pass;
  EXPECT_GT(failed, 0);
}

}  // namespace
}  // namespace dampbound
