// The tuner's "Save as scene" without a window (ui/tuner_save.hpp): tune, pin, save, and
// `check` passes on the file; edit a parameter in it and `check` fails. Also the scripted
// pins of `gui --pin` and what makes a run replayable.
#include "ui/tuner_save.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/analysis/expect.hpp"
#include "core/io/files.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/physics/error.hpp"
#include "tests/ui/ui_test_util.hpp"

namespace dampbound::ui {
namespace {

using ui_test::small_plane;

namespace fs = std::filesystem;

std::string temp_file(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / "dampbound_tuner_save";
  fs::create_directories(d);
  return (d / name).string();
}

TEST(TunerSave, TunePinSaveCheckPassesAndAnEditFails) {
  Tuner t(small_plane());
  Params p = t.params();
  p.gamma = 0.0015;  // "tuned"
  ASSERT_TRUE(t.set_params(p));
  const Pin under = pin_run(t, parse_pin_request("gamma=0.0005,name=under", t.params(), 1000));
  EXPECT_TRUE(under.replayable);  // a copy: the next pin may move the vector
  EXPECT_NE(under.result.outcome, Outcome::running);
  pin_run(t, parse_pin_request("gamma=0.002", t.params(), 1000));
  EXPECT_EQ(t.params().gamma, 0.0015);  // back on its own parameters, at the start
  EXPECT_EQ(t.session().state().iteration, 0);
  t.step(40);  // the current run: no verdict yet, so saving replays it

  const std::string path = temp_file("tuned.toml");
  std::vector<std::string> notes;
  const std::string summary = save_tuner_scene(t, path, default_expect_tolerance(), &notes);
  EXPECT_NE(summary.find("2 runs, 3 expectations"), std::string::npos) << summary;
  ASSERT_EQ(notes.size(), 1u);  // the current run, replayed
  EXPECT_NE(notes[0].find("current run"), std::string::npos);
  const SceneSpec back = load_scene(path);
  EXPECT_EQ(back.params.gamma, 0.0015);
  ASSERT_EQ(back.runs.size(), 2u);
  EXPECT_EQ(back.runs[0].label, "under");
  const auto results = check_expectations(back);
  ASSERT_GE(results.size(), 6u);
  for (const auto& r : results) EXPECT_TRUE(r.pass) << r.run << ": " << r.what << " " << r.measured;
  // The pins' measured verdicts are in the file.
  bool found = false;
  for (const Expectation& e : back.expectations)
    if (e.run == "under") {
      found = true;
      EXPECT_EQ(e.rule, StopRule::settled);  // the tuner's verdict rule (SPEC 8)
      EXPECT_EQ(e.outcome, under.result.outcome);
      ASSERT_TRUE(e.first_entry_min);
      EXPECT_LE(*e.first_entry_min, under.result.first_entry);
      EXPECT_GE(*e.first_entry_max, under.result.first_entry);
      if (under.result.outcome == Outcome::settled) {
        ASSERT_TRUE(e.settled_at_min);
        EXPECT_LE(*e.settled_at_min, under.result.settled_at);
        EXPECT_GE(*e.settled_at_max, under.result.settled_at);
      }
    }
  EXPECT_TRUE(found);
  // Edit the pinned run's gamma in the file: check fails.
  std::string text = read_file_text(path);
  const std::string from = "gamma = 0.0005";
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(), "gamma = 0.0009");
  { std::ofstream(path) << text; }
  int failed = 0;
  for (const auto& r : check_expectations(load_scene(path))) failed += !r.pass;
  EXPECT_GT(failed, 0);
}

// A run that played on past its verdict is saved with its result at the verdict, which is
// what check's replay (run_to_end, stopping there) measures.
TEST(TunerSave, ARunPastItsVerdictIsSavedAtItsVerdict) {
  Tuner t(small_plane());
  t.set_max_iterations(300);
  t.step(400);
  ASSERT_NE(t.session().result().outcome, Outcome::running);
  t.pin("played on");
  std::vector<std::string> notes;
  ExpectTolerance tol;
  tol.counts = true;
  tol.iteration_fraction = 0;  // +-2 exactly
  tol.displacement_factor = 1.5;
  const SceneSpec s = tuner_saved_scene(t, tol, &notes);
  EXPECT_TRUE(notes.empty());  // nothing replayed: both results are the runs' own
  for (const Expectation& e : s.expectations) {
    const RunResult replay = run_labelled(s, e.run, e.rule);
    EXPECT_EQ(*e.outcome, replay.outcome);
    if (e.settled_at_min) {
      EXPECT_EQ(*e.settled_at_max - 2, replay.settled_at);
    }
    if (e.first_entry_min) {
      EXPECT_EQ(*e.first_entry_max - 2, replay.first_entry);
    }
    EXPECT_EQ(*e.max_displacement_below, replay.max_displacement * tol.displacement_factor);
    EXPECT_EQ(*e.violations_max, replay.violations);
  }
}

TEST(TunerSave, RunsChangedByHandAreReplayed) {
  Tuner t(small_plane());
  EXPECT_TRUE(t.replayable());
  Params p = t.params();
  p.gamma = 0.001;
  ASSERT_TRUE(t.set_params(p));  // before the first step: still the scene's start
  EXPECT_TRUE(t.replayable());
  t.step(10);
  p.gamma = 0.0005;
  ASSERT_TRUE(t.set_params(p));  // mid-run
  EXPECT_FALSE(t.replayable());
  while (t.session().result().outcome == Outcome::running && t.step(500) > 0) {
  }
  const Pin& pin = t.pin("changed");
  EXPECT_FALSE(pin.replayable);
  t.reset();
  EXPECT_TRUE(t.replayable());
  t.displace(3, Vec3(0, 1, 0));
  EXPECT_FALSE(t.replayable());
  t.reset();
  t.perturb();
  EXPECT_FALSE(t.replayable());
  t.reset();
  std::vector<std::string> notes;
  const SceneSpec s = tuner_saved_scene(t, default_expect_tolerance(), &notes);
  ASSERT_EQ(s.runs.size(), 1u);
  // The saved expectation is the replay's, which check will see.
  const RunResult replay = run_labelled(s, "changed", StopRule::settled);
  EXPECT_EQ(s.expectations[1].outcome, replay.outcome);
  bool noted = false;
  for (const std::string& n : notes) noted = noted || n.find("changed by hand") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(TunerSave, PinsOfAnotherSceneAreLeftOut) {
  Tuner t(small_plane());
  t.pin("of the small plane");
  SceneSpec other = paper_plane_scene(6);
  other.name = "tiny";
  t.set_scene(other);
  std::vector<std::string> notes;
  const SceneSpec s = tuner_saved_scene(t, default_expect_tolerance(), &notes);
  EXPECT_TRUE(s.runs.empty());
  ASSERT_FALSE(notes.empty());
  EXPECT_NE(notes[0].find("another scene"), std::string::npos);
}

TEST(TunerSave, PinRequestErrorsNameTheFlag) {
  const Params base = default_params();
  for (const char* bad : {"gamma", "foo=1", "gamma=-1", "dt=0", "policy=soft", "m=abc",
                          "max_iterations=1.5", ""}) {
    SCOPED_TRACE(bad);
    try {
      parse_pin_request(bad, base, 1000);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--pin", 0), 0u) << e.what();
    }
  }
  const PinRequest r = parse_pin_request("gamma=0.0005,dt=0.1,policy=clamp,max_iterations=50,name=a b",
                                         base, 1000);
  EXPECT_EQ(r.params.gamma, 0.0005);
  EXPECT_EQ(r.params.dt, 0.1);
  EXPECT_EQ(r.params.policy, DampingPolicy::clamp);
  EXPECT_EQ(r.max_iterations, 50);
  EXPECT_EQ(r.name, "a b");
  EXPECT_EQ(r.params.m, base.m);
}

TEST(TunerSave, UnwritablePathIsAnInputError) {
  Tuner t(small_plane());
  EXPECT_THROW(save_tuner_scene(t, "/nonexistent-dir/x.toml", default_expect_tolerance()),
               InputError);
}

}  // namespace
}  // namespace dampbound::ui
