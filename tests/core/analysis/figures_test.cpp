// The paper's figures as data (core/analysis/figures.hpp): which runs with which parameters,
// each run's result and trace those of a Session, and the long CSV.
#include "core/analysis/figures.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "core/io/scene_file.hpp"
#include "dampbound/run/session.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

void expect_same_run(const SceneSpec& scene, const FigureRun& run) {
  Session session(scene, run.params, run.rules);
  const RunResult r = session.run_to_end();
  EXPECT_EQ(run.result.outcome, r.outcome);
  EXPECT_EQ(run.result.iterations, r.iterations);
  EXPECT_EQ(run.result.first_entry, r.first_entry);
  EXPECT_EQ(run.result.max_displacement, r.max_displacement);
  ASSERT_EQ(run.trace.size(), session.trace().size());
  for (size_t k = 0; k < run.trace.size(); ++k) {
    EXPECT_EQ(run.trace[k].iteration, session.trace()[k].iteration);
    EXPECT_EQ(run.trace[k].watched.displacement, session.trace()[k].watched.displacement);
  }
}

TEST(Figures, Fig1IsThreeSessionRuns) {
  const SceneSpec plane = paper_plane_scene(10);  // small: the same runs, faster
  const FigureData f = figure_fig1(plane);
  EXPECT_EQ(f.name, "fig1");
  EXPECT_FALSE(f.log_y);
  EXPECT_EQ(f.watched, plane.watched);
  EXPECT_DOUBLE_EQ(f.restore_threshold, 0.01 * 5.0);  // 1% of the 5 cm pull
  ASSERT_EQ(f.runs.size(), 3u);
  const double gammas[] = {0.0005, 0.001, 0.002};
  const char* labels[] = {"gamma = 0.0005", "gamma = 0.001", "gamma = 0.002"};
  for (size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(labels[k]);
    const FigureRun& run = f.runs[k];
    EXPECT_EQ(run.label, labels[k]);
    EXPECT_EQ(run.params.gamma, gammas[k]);
    EXPECT_EQ(run.params.m, 0.001);
    EXPECT_EQ(run.params.kappa, 0.001);
    EXPECT_EQ(run.params.dt, 0.05);
    EXPECT_EQ(run.params.policy, DampingPolicy::fixed);
    EXPECT_EQ(run.rules.max_iterations, 1000);
    EXPECT_EQ(run.trace.size(), size_t(run.result.iterations));
    expect_same_run(plane, run);
  }
}

/// SPEC 8: fig1 and fig2 reproduce the paper, so they stop at the first entry even when the
/// plane scene given asks for the settled rule; the runs are those of the default scene.
TEST(Figures, PaperFiguresStopAtTheFirstEntryWhateverTheScenesRule) {
  const SceneSpec plane = paper_plane_scene(6);
  SceneSpec settled = plane;
  settled.rules.rule = StopRule::settled;
  for (auto figure : {&figure_fig1, &figure_fig2}) {
    const FigureData a = figure(plane), b = figure(settled);
    ASSERT_EQ(a.runs.size(), b.runs.size());
    for (size_t k = 0; k < a.runs.size(); ++k) {
      SCOPED_TRACE(a.name + " " + a.runs[k].label);
      EXPECT_EQ(b.runs[k].rules.rule, StopRule::first_entry);
      EXPECT_EQ(b.runs[k].result.iterations, a.runs[k].result.iterations);
      EXPECT_EQ(b.runs[k].result.outcome, a.runs[k].result.outcome);
    }
  }
}

TEST(Figures, Fig2UsesTheUpperBoundPolicy) {
  const SceneSpec plane = paper_plane_scene(6);
  const FigureData f = figure_fig2(plane);
  EXPECT_EQ(f.name, "fig2");
  EXPECT_TRUE(f.log_y);
  ASSERT_EQ(f.runs.size(), 2u);
  EXPECT_EQ(f.runs[0].label, "gamma = 1 x upper");
  EXPECT_EQ(f.runs[1].label, "gamma = 1.05 x upper");
  for (const FigureRun& run : f.runs) {
    EXPECT_EQ(run.params.policy, DampingPolicy::upper);
    EXPECT_EQ(run.params.m, 0.005);
    EXPECT_EQ(run.params.kappa, 0.1);
    EXPECT_EQ(run.rules.max_iterations, 10000);
    expect_same_run(plane, run);
  }
  EXPECT_EQ(f.runs[1].params.factor, 1.05);
}

TEST(Figures, SceneFigureJudgesBySettledAndGoesLogWhenARunDiverges) {
  SceneSpec s = load_scene(test::source_path("scenes/two-node.toml"));
  FigureData own = figure_scene(s);
  EXPECT_EQ(own.name, "two-node");
  EXPECT_EQ(own.title, s.description);
  ASSERT_EQ(own.runs.size(), 1u);
  EXPECT_EQ(own.runs[0].label, "two-node");
  EXPECT_EQ(own.runs[0].rules.rule, StopRule::settled);
  EXPECT_EQ(own.runs[0].result.outcome, Outcome::settled);
  EXPECT_EQ(own.runs[0].result.iterations, 1000);
  EXPECT_FALSE(own.log_y);
  expect_same_run(s, own.runs[0]);
  RunSpec wild;  // dt^2 kappa/m = 9 > 4: the semi-implicit step is unstable (SPEC 7)
  wild.label = "wild";
  wild.params = s.params;
  wild.params.dt = 3.0;
  wild.rules = s.rules;
  s.runs.push_back(wild);
  const FigureData two = figure_scene(s);
  ASSERT_EQ(two.runs.size(), 1u);  // the declared runs replace the scene's own parameters
  EXPECT_EQ(two.runs[0].result.outcome, Outcome::diverged);
  EXPECT_TRUE(two.log_y);
}

TEST(Figures, CsvHasOneHeaderAndEveryRunsRows) {
  FigureData f;
  for (const char* label : {"a", "b"}) {
    FigureRun run;
    run.label = label;
    run.trace.resize(2);
    run.trace[0].iteration = 1, run.trace[1].iteration = 2;
    f.runs.push_back(run);
  }
  std::ostringstream out;
  write_figure_csv(out, f);
  const std::string csv = out.str();
  EXPECT_EQ(csv.substr(0, 14), "run,iteration,");
  size_t lines = 0, headers = 0;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line); ++lines) headers += line.rfind("run,", 0) == 0;
  EXPECT_EQ(lines, 5u);
  EXPECT_EQ(headers, 1u);
  EXPECT_NE(csv.find("\na,1,"), std::string::npos);
  EXPECT_NE(csv.find("\nb,2,"), std::string::npos);
}

}  // namespace
}  // namespace dampbound
