// The tuner's plots and export without a window: pins overlaid and removable, the band
// coarsened for drawing, the long CSV of all runs.
#include "ui/tuner_plots.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/io/files.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/run/scene.hpp"
#include "ui/gui_export.hpp"
#include "ui/tuner_export.hpp"

namespace dampbound::ui {
namespace {

SceneSpec tiny() {
  SceneSpec s;
  s.name = "tiny";
  GridSpec g;
  g.nx = g.nz = 6;
  g.spacing = 0.57;
  s.model = make_grid(g);
  s.watched = 14;
  Perturbation p;
  p.node = 14;
  p.displacement = Vec3(0, 5, 0);
  s.perturbations.push_back(p);
  return s;
}

bool has_series(const PlotSpec& p, const std::string& label) {
  for (const auto& s : p.series)
    if (s.label.find(label) != std::string::npos) return true;
  return false;
}

TEST(TunerPlots, PinsAreOverlaidUntilHiddenOrRemoved) {
  Tuner t(tiny());
  t.step(30);
  t.pin("slow one");
  t.reset();
  t.step(10);
  TunerPlotOptions o;
  PlotSpec d = tuner_displacement_plot(t, o);
  EXPECT_TRUE(has_series(d, "slow one"));
  EXPECT_TRUE(has_series(d, "current"));
  EXPECT_TRUE(has_series(d, "max over nodes"));
  ASSERT_FALSE(d.ref_lines.empty());
  EXPECT_EQ(d.ref_lines[0].axis, LineAxis::y);               // the threshold, horizontal
  EXPECT_DOUBLE_EQ(d.ref_lines[0].at, 0.05);                 // 1 % of the 5 cm perturbation
  for (size_t i = 1; i < d.ref_lines.size(); ++i)            // the rest: verdict markers
    EXPECT_EQ(d.ref_lines[i].axis, LineAxis::x);
  EXPECT_EQ(d.series.back().label.rfind("current", 0), 0u);  // live run drawn last
  PlotSpec e = tuner_envelope_plot(t, o);
  EXPECT_TRUE(has_series(e, "slow one"));
  EXPECT_TRUE(has_series(e, "lower bound"));
  EXPECT_TRUE(e.y.log);
  ASSERT_TRUE(e.y.min && e.y.max);
  EXPECT_LT(*e.y.min, 0.002);
  t.pins()[0].visible = false;
  EXPECT_FALSE(has_series(tuner_displacement_plot(t, o), "slow one"));
  t.pins()[0].visible = true;
  o.show_pins = false;
  EXPECT_FALSE(has_series(tuner_displacement_plot(t, o), "slow one"));
  o.show_pins = true;
  t.unpin(0);
  EXPECT_FALSE(has_series(tuner_envelope_plot(t, o), "slow one"));
  o.log_y = true;
  EXPECT_TRUE(tuner_displacement_plot(t, o).y.log);
}

// A pin of another scene watched another mesh's node: after a scene switch it stays in the
// list but is not drawn over the new scene's plots; back on its scene it is drawn again.
TEST(TunerPlots, PinsOfAnotherSceneAreNotOverlaid) {
  Tuner t(tiny());
  t.step(30);
  t.pin("tiny's run");
  SceneSpec other = tiny();
  other.name = "other";
  t.set_scene(other);
  t.step(5);
  TunerPlotOptions o;
  ASSERT_EQ(t.pins().size(), 1u);
  EXPECT_FALSE(has_series(tuner_displacement_plot(t, o), "tiny's run"));
  EXPECT_FALSE(has_series(tuner_envelope_plot(t, o), "tiny's run"));
  t.set_scene(tiny());
  EXPECT_TRUE(has_series(tuner_displacement_plot(t, o), "tiny's run"));
}

// The envelope's curves are the watched node's gamma_i; the exact limit is of the user's gamma,
// so on a node damped 3x it is drawn 3x higher, labelled so (it sat 3x too low beside the
// node's own safe bound, which the same limit approaches).
TEST(TunerPlots, TheExactLimitIsDrawnInTheWatchedNodesGamma) {
  SceneSpec scene = tiny();
  scene.model.gamma_scale[14] = 3;
  Tuner t(std::move(scene));
  t.step(5);
  const std::optional<double> exact = t.exact_gamma_max();
  ASSERT_TRUE(exact && *exact > 0);
  auto exact_line = [](const PlotSpec& p) -> const PlotRefLine* {
    for (const PlotRefLine& l : p.ref_lines)
      if (l.label.rfind("exact linear limit", 0) == 0) return &l;
    return nullptr;
  };
  const PlotSpec scaled = tuner_envelope_plot(t, {});
  const PlotRefLine* line = exact_line(scaled);
  ASSERT_NE(line, nullptr);
  EXPECT_DOUBLE_EQ(line->at, 3 * *exact);
  EXPECT_EQ(line->label, "exact linear limit x gamma_scale 3");
  t.watch(15);  // an unscaled node: the limit itself, the label as before
  const PlotSpec unscaled = tuner_envelope_plot(t, {});
  const PlotRefLine* plain = exact_line(unscaled);
  ASSERT_NE(plain, nullptr);
  EXPECT_DOUBLE_EQ(plain->at, *exact);
  EXPECT_EQ(plain->label, "exact linear limit");
}

TEST(TunerPlots, VerdictMarkersShowEntryExitAndSettled) {
  RunResult r;
  EXPECT_TRUE(verdict_markers(r).empty());
  r.first_entry = 230;
  r.left_at = 231;
  r.outcome = Outcome::settled;
  r.settled_at = 262;
  const std::vector<PlotRefLine> m = verdict_markers(r);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0].label, "first entry 230");
  EXPECT_EQ(m[0].axis, LineAxis::x);
  EXPECT_DOUBLE_EQ(m[0].at, 230);
  EXPECT_EQ(m[1].label, "left at 231");
  EXPECT_EQ(m[2].label, "settled at 262");
  EXPECT_FALSE(m[2].dashed);
  r.outcome = Outcome::diverged;
  r.iterations = 300;
  const std::vector<PlotRefLine> d = verdict_markers(r);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[2].label, "diverged at 300");
  // The live plot carries them.
  Tuner t(load_scene(DAMPBOUND_SOURCE_DIR "/scenes/two-node.toml"));
  Params p = t.params();
  p.gamma = 0;
  ASSERT_TRUE(t.set_params(p));
  t.step(40);
  const PlotSpec spec = tuner_displacement_plot(t, TunerPlotOptions{});
  int marks = 0;
  for (const PlotRefLine& v : spec.ref_lines)
    marks += v.label == "first entry 31" || v.label.rfind("left at ", 0) == 0;
  EXPECT_EQ(marks, 2);
}

// Before the first step the envelope is not blank: the watched node's lower bound and the
// user's gamma are drawn across it, and the log axis takes them in.
TEST(TunerPlots, BeforeTheFirstStepTheLowerBoundAndTheUsersGammaAreDrawn) {
  SceneSpec scene = load_scene(DAMPBOUND_SOURCE_DIR "/scenes/two-node.toml");
  scene.params.gamma = 0.0005;  // below the lower bound 0.002, so that the lines are two
  Tuner t(std::move(scene));
  ASSERT_EQ(t.session().state().iteration, 0);
  const PlotSpec p = tuner_envelope_plot(t, TunerPlotOptions{});
  const auto i = static_cast<size_t>(t.session().watched());
  const Model& m = t.session().model();
  int drawn = 0;
  for (const PlotSeries& s : p.series) {
    if (s.label.rfind("lower bound", 0) == 0) {
      ASSERT_EQ(s.y.size(), 2u);
      EXPECT_EQ(s.y[0], m.lower_bound[i]);
      ++drawn;
    } else if (s.label == "user gamma") {
      ASSERT_EQ(s.y.size(), 2u);
      EXPECT_EQ(s.y[0], m.gamma[i]);
      ++drawn;
    }
  }
  EXPECT_EQ(drawn, 2);
  EXPECT_LT(p.y.min, std::min(m.lower_bound[i], m.gamma[i]));
  EXPECT_GT(p.y.max, std::max(m.lower_bound[i], m.gamma[i]));
}

TEST(TunerPlots, BandIsCoarsenedConservatively) {
  PlotBand b;
  const double inf = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 1000; ++i) {
    b.x.push_back(i);
    b.y_lo.push_back(i < 500 ? 1.0 : 2.0);
    b.y_hi.push_back(i < 500 ? inf : 10.0 + (i % 7));
  }
  simplify_band(b, 100);
  ASSERT_LE(b.x.size(), 202u);
  EXPECT_EQ(b.x.front(), 0);
  EXPECT_EQ(b.x.back(), 999);
  // The constant first half became its two ends.
  size_t first_half = 0;
  for (double x : b.x) first_half += x < 490;
  EXPECT_LE(first_half, 2u);
  for (size_t i = 0; i + 1 < b.x.size(); ++i)
    if (b.x[i] > 500) {
      EXPECT_EQ(b.y_hi[i], 10.0);  // the smallest upper edge of its bucket
    }
}

/// The simplified band's edge at x (linear between its samples; not at a step's x).
double band_edge_at(const PlotBand& b, const std::vector<double>& edge, double x) {
  for (size_t i = 0; i + 1 < b.x.size(); ++i)
    if (b.x[i] <= x && x <= b.x[i + 1] && b.x[i + 1] > b.x[i])
      return edge[i] + (edge[i + 1] - edge[i]) * (x - b.x[i]) / (b.x[i + 1] - b.x[i]);
  return std::nan("");
}

TEST(TunerPlots, ACoarsenedBandKeepsAStepWhereItIs) {
  // The upper edge drops from 20 to 10 at sample 505, inside the bucket 500..510. Coarsened,
  // it stays 20 up to that bucket (it used to slope down from sample 490, ahead of the curve
  // drawn over it) and never lies above the data.
  PlotBand b;
  std::vector<double> hi;
  for (int i = 0; i < 1000; ++i) {
    b.x.push_back(i);
    b.y_lo.push_back(1.0);
    hi.push_back(i < 505 ? 20.0 : 10.0);
  }
  b.y_hi = hi;
  simplify_band(b, 100);
  for (int x = 1; x < 1000; ++x) {
    if (x % 10 == 0) continue;  // a bucket's edge: a vertical step in the coarse band
    const double edge = band_edge_at(b, b.y_hi, x);
    EXPECT_LE(edge, hi[static_cast<size_t>(x)]) << x;
    if (x < 500) {
      EXPECT_EQ(edge, 20.0) << x;
    }
    if (x > 510) {
      EXPECT_EQ(edge, 10.0) << x;
    }
  }
}

TEST(TunerPlots, FlatRunsKeepTheirEndsOnly) {
  PlotSeries s;
  s.x = {0, 1, 2, 3, 4, 5, 6};
  s.y = {1, 1, 1, 2, 2, 2, 2};
  drop_flat_runs(s);
  EXPECT_EQ(s.x, (std::vector<double>{0, 2, 3, 6}));
  EXPECT_EQ(s.y, (std::vector<double>{1, 1, 2, 2}));
  PlotSeries wiggle;
  wiggle.x = {0, 1, 2, 3};
  wiggle.y = {1, 2, 1, 2};
  drop_flat_runs(wiggle);
  EXPECT_EQ(wiggle.x.size(), 4u);
}

TEST(TunerPlots, HeadroomCapsTheLogAxis) {
  PlotSpec p;
  p.y.log = true;
  PlotSeries s;
  s.x = {1, 2, 3};
  s.y = {0.001, 1e9, 0.01};
  p.series.push_back(s);
  envelope_headroom(p, 1.0, 0.5);
  ASSERT_TRUE(p.y.min && p.y.max);
  EXPECT_LT(*p.y.min, 0.001);
  EXPECT_NEAR(std::log10(*p.y.max), 3.0, 1e-9);  // data up to 1, the same span again above
}

TEST(TunerExport, LongCsvHasOneHeaderAndARunColumn) {
  Tuner t(tiny());
  t.step(12);
  t.pin("a, quoted");
  t.reset();
  t.step(5);
  std::ostringstream csv;
  write_runs_trace_csv(csv, t);
  std::istringstream in(csv.str());
  std::string line;
  int rows = 0, headers = 0, pinned = 0;
  while (std::getline(in, line)) {
    if (line.rfind("run,iteration", 0) == 0)
      ++headers;
    else
      ++rows;
    if (line.rfind("\"a, quoted\",", 0) == 0) ++pinned;
  }
  EXPECT_EQ(headers, 1);
  EXPECT_EQ(rows, 17);
  EXPECT_EQ(pinned, 12);
  EXPECT_EQ(csv.str().find("nan"), std::string::npos);
  std::ostringstream runs;
  write_runs_summary_csv(runs, t);
  EXPECT_NE(runs.str().find("\"a, quoted\",tiny,14,"), std::string::npos);
}

TEST(TunerExport, WritesFilesAtomicallyAndRejectsBadPrefixes) {
  Tuner t(tiny());
  t.step(3);
  const auto dir = std::filesystem::temp_directory_path() / "dampbound_tuner_export_test";
  std::filesystem::remove_all(dir);
  const ExportPaths p = export_paths((dir / "sub").string(), "run1");
  EXPECT_NE(p.plots_png.find("run1_plots.png"), std::string::npos);
  export_csv(t, p);
  EXPECT_TRUE(std::filesystem::exists(p.traces_csv));
  EXPECT_TRUE(std::filesystem::exists(p.runs_csv));
  // The current step for ParaView: the tiny scene's nodes and springs at iteration 3.
  const std::string vtu = read_file_text(p.step_vtu);
  EXPECT_NE(vtu.find("NumberOfPoints=\"" + std::to_string(t.session().model().spec().node_count())),
            std::string::npos);
  EXPECT_NE(vtu.find("Name=\"effective_damping\""), std::string::npos);
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir / "sub"))
    files += e.is_regular_file();
  EXPECT_EQ(files, 3);  // no temporary file left behind
  EXPECT_THROW(export_paths(dir.string(), "a/b"), InputError);
  EXPECT_THROW(export_paths(dir.string(), ""), InputError);
  std::filesystem::remove_all(dir);
}

TEST(TunerExport, RunsCsvHasTheBandHistoryAndLeavesOutAnUnfinishedRun) {
  Tuner t(tiny());
  t.step(t.session().rules().max_iterations);  // to the verdict under the settled rule
  const RunResult done = t.session().result();
  ASSERT_NE(done.outcome, Outcome::running);
  t.pin("to the limit");
  t.reset();
  t.step(7);  // the current run: unfinished
  EXPECT_FALSE(export_includes_current(t, false));
  EXPECT_TRUE(export_includes_current(t, true));
  std::ostringstream runs;
  write_runs_summary_csv(runs, t, export_includes_current(t, false));
  std::istringstream in(runs.str());
  std::string header, row, extra;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_FALSE(std::getline(in, extra)) << "the unfinished current run is left out: " << extra;
  EXPECT_EQ(header,
            "run,scene,watched,m,kappa,gamma,dt,policy,factor,rule,outcome,first_entry,left_at,"
            "settled_at,diverged_at,verdict,iterations,max_displacement,violations,"
            "unstabilisable");
  // The pin's verdict in the settled rule's words, with the iteration it settled at (not the
  // iteration limit at which the rule decides).
  const auto field = [](const std::string& line, int k) {
    std::istringstream f(line);
    std::string v;
    for (int i = 0; i <= k; ++i) std::getline(f, v, ',');
    return v;
  };
  EXPECT_EQ(field(row, 9), "settled");
  EXPECT_EQ(field(row, 10), to_string(done.outcome));
  EXPECT_EQ(field(row, 11), done.first_entry > 0 ? std::to_string(done.first_entry) : "");
  EXPECT_EQ(field(row, 13), done.settled_at > 0 ? std::to_string(done.settled_at) : "");
  EXPECT_EQ(field(row, 14), "");
  if (done.outcome == Outcome::settled) {
    EXPECT_NE(field(row, 13), field(row, 16));
  }
  std::ostringstream with_current;
  write_runs_summary_csv(with_current, t, true);
  EXPECT_NE(with_current.str().find("current: "), std::string::npos);
  std::ostringstream traces;
  write_runs_trace_csv(traces, t, false);
  EXPECT_EQ(traces.str().find("current: "), std::string::npos);
}

TEST(TunerExport, PlotsDrawEveryStepOfThePinsAsFigureDoes) {
  // A pin longer than the plotting buckets: the window draws its min/max reduction (a
  // staircase at export size); the export draws every step, as `figure` does.
  Tuner t(tiny());
  t.step(t.session().rules().max_iterations);
  const Pin& pin = t.pin("long");
  ASSERT_GT(pin.trace.size(), kPlotBuckets);
  t.reset();
  t.step(5);
  const std::vector<PlotSpec> plots = export_plot_specs(t, {}, false);
  ASSERT_EQ(plots.size(), 1u);  // the unfinished run's damping bounds are not drawn
  const PlotSpec& d = plots[0];
  ASSERT_FALSE(has_series(d, "current"));
  const PlotSeries* s = nullptr;
  for (const auto& ser : d.series)
    if (ser.label.rfind("long", 0) == 0) s = &ser;
  ASSERT_NE(s, nullptr);
  // Every drawn point lies on the trace; flat runs drop interior points only.
  size_t on = 0;
  for (size_t i = 0; i < s->x.size(); ++i) {
    const auto& st = pin.trace.at(static_cast<size_t>(s->x[i]) - 1);
    ASSERT_EQ(st.iteration, static_cast<int>(s->x[i]));
    on += st.watched.displacement == s->y[i];
  }
  EXPECT_EQ(on, s->x.size());
  EXPECT_GT(s->x.size(), kPlotBuckets);
  EXPECT_EQ(export_plot_specs(t, {}, true).size(), 2u);
}

}  // namespace
}  // namespace dampbound::ui
