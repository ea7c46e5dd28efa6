// The tuner's state without a window (ui/tuner.hpp): parameter changes mid-run, playback,
// divergence, pinning, watching, displacing and cutting through the screen-space cut tool.
#include "ui/tuner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "core/io/report.hpp"
#include "core/io/scene_file.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/run/scene.hpp"
#include "ui/mesh_pick.hpp"
#include "tests/ui/ui_test_util.hpp"

namespace dampbound::ui {
namespace {

using ui_test::small_plane;

TEST(Tuner, StartsPausedAtTheScenesParameters) {
  Tuner t(small_plane());
  EXPECT_FALSE(t.playing());
  EXPECT_EQ(t.advance(), 0);
  EXPECT_EQ(t.session().state().iteration, 0);
  EXPECT_DOUBLE_EQ(t.params().gamma, default_params().gamma);
}

// A scene that gives a damping ratio (zeta) runs with the gamma it means, whether the tuner
// starts with it or opens it later (the Open button and the scene combo call open_scene).
TEST(Tuner, AScenesZetaIsResolvedWhenTheTunerOpensIt) {
  const std::string path = ::testing::TempDir() + "zeta-plane.toml";
  {
    std::ofstream out(path);
    out << "[grid]\nnx = 6\nnz = 6\nspacing = 1.0\nanchors = true\n[params]\nzeta = 0.5\n";
  }
  const double want = 0.5 * 2 * std::sqrt(default_params().m * default_params().kappa);
  Tuner t(small_plane());
  std::string error;
  ASSERT_TRUE(t.open_scene(path, &error)) << error;
  EXPECT_DOUBLE_EQ(t.params().gamma, want);
  EXPECT_FALSE(t.params().zeta.has_value());
  Tuner fresh(load_scene(path));
  EXPECT_DOUBLE_EQ(fresh.params().gamma, want);
}

/// Every free node's zeta_i = gamma_i / 2 sqrt(m_i kappa_i) equals `zeta` (nodes with a bound).
void expect_every_node_at_zeta(const Model& m, double zeta) {
  int nodes = 0;
  for (int i = 0; i < m.spec().node_count(); ++i) {
    const auto k = static_cast<size_t>(i);
    if (m.spec().fixed[k] || !(m.lower_bound[k] > 0)) continue;
    ++nodes;
    ASSERT_NEAR(m.gamma[k] / m.lower_bound[k], zeta, 1e-12 * zeta) << "node " << i;
  }
  EXPECT_GT(nodes, 0);
}

// SPEC 10 in the tuner: in zeta mode the slider sets the ratio and each node's gamma_i is
// resolved from it, on a scene whose nodes have their own lower bounds too (stiff-region:
// 4x heavier, 10x stiffer square), and m or kappa moved keep the ratio.
TEST(Tuner, ZetaModeResolvesEachNodesGammaFromTheRatio) {
  Tuner t(load_scene(DAMPBOUND_SOURCE_DIR "/scenes/stiff-region.toml"));
  EXPECT_FALSE(t.zeta_mode());
  EXPECT_FALSE(t.zeta_resolved());  // gamma_scale 1: the square's nodes have other ratios
  t.step(3);
  std::string error;
  ASSERT_TRUE(t.set_zeta(0.7, &error)) << error;
  EXPECT_TRUE(t.zeta_mode());
  EXPECT_TRUE(t.zeta_resolved());
  EXPECT_EQ(t.session().state().iteration, 0);  // resolved: the run restarted, and says so
  EXPECT_NE(t.notice().find("restarted"), std::string::npos);
  EXPECT_DOUBLE_EQ(t.zeta(), 0.7);
  expect_every_node_at_zeta(t.session().model(), 0.7);
  EXPECT_EQ(zeta_text(t.session().model()), "0.7");
  Params p = t.params();
  p.m *= 3;
  p.kappa *= 0.5;
  ASSERT_TRUE(t.set_params(p, &error)) << error;
  EXPECT_NEAR(t.zeta(), 0.7, 1e-15);
  expect_every_node_at_zeta(t.session().model(), 0.7);
  // A gamma set as such (Suggest's apply) moves zeta with it.
  p = t.params();
  p.gamma *= 2;
  ASSERT_TRUE(t.set_params(p, &error)) << error;
  EXPECT_NEAR(t.zeta(), 1.4, 1e-14);
  expect_every_node_at_zeta(t.session().model(), 1.4);
  EXPECT_FALSE(t.set_zeta(-1, &error));
  EXPECT_NE(error.find("zeta"), std::string::npos);
}

// On a scene whose nodes share the lower bound 2 sqrt(m kappa) zeta mode needs no restart.
TEST(Tuner, ZetaModeOnAPlainMeshKeepsTheRun) {
  Tuner t(small_plane());
  EXPECT_TRUE(t.zeta_resolved());
  t.step(3);
  ASSERT_TRUE(t.set_zeta(0.25));
  EXPECT_EQ(t.session().state().iteration, 3);
  expect_every_node_at_zeta(t.session().model(), 0.25);
  t.set_zeta_mode(false);
  Params p = t.params();
  p.m *= 4;  // gamma mode: gamma held, zeta halves
  ASSERT_TRUE(t.set_params(p));
  expect_every_node_at_zeta(t.session().model(), 0.125);
  EXPECT_EQ(zeta_text(t.session().model()), "0.125");
}

TEST(Tuner, SaysTheDisplacementOfTheStateAsItIsNow) {
  // At the perturbed start (no step yet) the centre node sits 5 cm out: the status said
  // "max |x - X| 0 cm" there, from an empty trace.
  Tuner t(small_plane());
  ASSERT_TRUE(t.session().trace().empty());
  EXPECT_NEAR(t.max_displacement_now(), 5.0, 1e-12);
  EXPECT_NEAR(t.watched_displacement_now(), 5.0, 1e-12);
  t.step(3);
  EXPECT_DOUBLE_EQ(t.max_displacement_now(), t.session().trace().back().max_displacement);
  t.displace(t.session().watched(), Vec3(0, 2, 0));  // a drag: not in the trace until a step
  EXPECT_NE(t.max_displacement_now(), t.session().trace().back().max_displacement);
}

TEST(Tuner, ParameterChangeTakesEffectAtTheNextStepWithoutRestart) {
  Tuner t(small_plane());
  t.step(5);
  Params p = t.params();
  p.gamma = 0.0005;
  p.kappa = 0.004;
  ASSERT_TRUE(t.set_params(p));
  t.step(1);
  const auto& tr = t.session().trace();
  ASSERT_EQ(tr.size(), 6u);  // the trace goes on: no restart
  EXPECT_EQ(t.session().state().iteration, 6);
  EXPECT_DOUBLE_EQ(tr[4].watched.gamma, default_params().gamma);
  EXPECT_DOUBLE_EQ(tr[5].watched.gamma, 0.0005);
  EXPECT_DOUBLE_EQ(tr[4].watched.lower, lower_bound(0.001, 0.001));
  EXPECT_DOUBLE_EQ(tr[5].watched.lower, lower_bound(0.001, 0.004));
  // The policy too.
  p.policy = DampingPolicy::lower;
  ASSERT_TRUE(t.set_params(p));
  t.step(1);
  EXPECT_DOUBLE_EQ(tr.back().watched.gamma_eff, tr.back().watched.lower);
}

TEST(Tuner, InvalidParametersAreRefusedAndChangeNothing) {
  Tuner t(small_plane());
  const Params before = t.params();
  Params p = before;
  p.m = 0;
  std::string why;
  EXPECT_FALSE(t.set_params(p, &why));
  EXPECT_NE(why.find('m'), std::string::npos);
  p = before;
  p.gamma = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(t.set_params(p, &why));
  EXPECT_DOUBLE_EQ(t.params().m, before.m);
  EXPECT_DOUBLE_EQ(t.params().gamma, before.gamma);
}

TEST(Tuner, PlaybackStepsPerFrame) {
  Tuner t(small_plane());
  t.playback().steps_per_frame = 7;
  t.playback().frame_budget_seconds = -1;  // no time limit: exactly the steps asked for
  EXPECT_EQ(t.advance(), 0);
  ASSERT_TRUE(t.set_playing(true));
  EXPECT_EQ(t.advance(), 7);
  EXPECT_EQ(t.advance(), 7);
  EXPECT_EQ(t.session().state().iteration, 14);
  t.set_playing(false);
  EXPECT_EQ(t.step(3), 3);  // single steps while paused
  EXPECT_EQ(t.total_steps(), 17);
}

TEST(Tuner, AFrameStopsSteppingAtItsTimeBudget) {
  // 10000 steps per frame would hold a frame for seconds on a large mesh: the budget ends the
  // frame's stepping early, after at least one step. A zero budget makes that exact.
  Tuner t(small_plane());
  t.playback().steps_per_frame = 10000;
  t.playback().frame_budget_seconds = 0;
  ASSERT_TRUE(t.set_playing(true));
  EXPECT_EQ(t.advance(), 1);
  EXPECT_EQ(t.budget_cut().taken, 1);  // said, not silent: 1 of 10000 steps this frame
  EXPECT_EQ(t.budget_cut().asked, 10000);
  EXPECT_EQ(t.advance(), 1);
  EXPECT_EQ(t.session().state().iteration, 2);
  EXPECT_EQ(t.step(5), 5);  // single steps (the Step buttons) keep their count
  t.playback().frame_budget_seconds = 1e9;
  EXPECT_EQ(t.advance(), 10000);
  EXPECT_EQ(t.budget_cut().asked, 0);  // every step asked: the budget did not bind
}

TEST(Tuner, DivergenceStopsPlaybackCleanlyUntilReset) {
  Tuner t(small_plane());
  Params p = t.params();
  p.kappa = 10;
  p.gamma = 0;
  p.dt = 0.2;
  ASSERT_TRUE(t.set_params(p));
  t.playback().steps_per_frame = 50;
  ASSERT_TRUE(t.set_playing(true));
  for (int i = 0; i < 100 && t.playing(); ++i) t.advance();
  EXPECT_FALSE(t.playing());
  EXPECT_EQ(t.session().result().outcome, Outcome::diverged);
  EXPECT_EQ(t.session().state().iteration, t.session().result().iterations);
  EXPECT_NE(t.notice().find("diverged at"), std::string::npos);
  EXPECT_FALSE(t.can_step());
  EXPECT_FALSE(t.set_playing(true));
  EXPECT_EQ(t.step(5), 0);
  ASSERT_FALSE(t.session().workspace().status.empty());
  t.reset();  // same parameters: it can step again (and diverges again, at once)
  EXPECT_TRUE(t.can_step());
  EXPECT_EQ(t.session().state().iteration, 0);
  // Nothing of the diverged step stays: no node is coloured, no status read, from it.
  EXPECT_TRUE(t.session().workspace().status.empty());
  EXPECT_TRUE(t.session().workspace().upper_bound.empty());
  ASSERT_TRUE(t.set_params(default_params()));
  t.reset();
  EXPECT_EQ(t.step(20), 20);
  EXPECT_TRUE(t.set_playing(true));
}

TEST(Tuner, PauseAtTheVerdictWhenAsked) {
  Tuner t(small_plane());
  t.playback().pause_at_verdict = true;
  t.playback().steps_per_frame = 1000;
  t.playback().frame_budget_seconds = -1;  // all 1000 steps in one frame, however slow the build
  t.set_playing(true);
  t.advance();
  EXPECT_FALSE(t.playing());
  EXPECT_NE(t.session().result().outcome, Outcome::running);
  EXPECT_EQ(t.session().state().iteration, t.session().result().iterations);
  // The tuner judges by the settled rule (SPEC 8): the verdict is final at the limit.
  EXPECT_EQ(t.session().rules().rule, StopRule::settled);
  EXPECT_EQ(t.session().result().iterations, t.session().rules().max_iterations);
  EXPECT_NE(t.notice().find("paused at the verdict (the iteration limit"), std::string::npos)
      << t.notice();
}

TEST(Tuner, AnUndampedOscillatorEntersLeavesAndThePinKeepsItAll) {
  Tuner t(load_scene(DAMPBOUND_SOURCE_DIR "/scenes/two-node.toml"));
  Params p = t.params();
  p.gamma = 0;
  ASSERT_TRUE(t.set_params(p));
  t.step(40);
  const RunResult& r = t.session().result();
  EXPECT_EQ(r.outcome, Outcome::running);  // no green "restored at 31" any more
  EXPECT_EQ(r.first_entry, 31);
  EXPECT_GT(r.left_at, 31);
  EXPECT_NE(verdict_short(r).find("entered at 31, left at"), std::string::npos) << verdict_short(r);
  t.playback().pause_at_verdict = true;
  t.step(5000);
  EXPECT_EQ(t.session().result().outcome, Outcome::not_settled);
  const Pin& pin = t.pin();
  EXPECT_EQ(pin.result.outcome, Outcome::not_settled);
  EXPECT_EQ(pin.result.first_entry, 31);
  EXPECT_EQ(pin.result.left_at, r.left_at);
  EXPECT_EQ(pin.rules.rule, StopRule::settled);
}

TEST(Tuner, PinsKeepACopyOfTheTraceAndDistinctColours) {
  Tuner t(small_plane());
  t.step(10);
  Pin& a = t.pin("first");
  EXPECT_EQ(a.name, "first");
  EXPECT_EQ(a.trace.size(), 10u);
  EXPECT_EQ(a.reduced.size(), 10u);
  Params p = t.params();
  p.gamma = 0.0005;
  ASSERT_TRUE(t.set_params(p));
  t.reset();
  t.step(4);
  const Pin& b = t.pin();
  EXPECT_EQ(b.name, params_label(p));
  EXPECT_NE(b.name.find("gamma 0.0005"), std::string::npos);
  ASSERT_EQ(t.pins().size(), 2u);
  EXPECT_EQ(t.pins()[0].trace.size(), 10u);  // unchanged by the reset and new steps
  EXPECT_EQ(t.pins()[1].trace.size(), 4u);
  EXPECT_DOUBLE_EQ(t.pins()[1].params.gamma, 0.0005);
  EXPECT_NE(t.pins()[0].color, t.pins()[1].color);
  EXPECT_NE(t.pins()[0].color, t.current_color());
  EXPECT_NE(t.pins()[1].color, t.current_color());
  t.unpin(0);
  ASSERT_EQ(t.pins().size(), 1u);
  EXPECT_EQ(t.pins()[0].trace.size(), 4u);
  t.unpin(7);  // out of range: ignored
  EXPECT_EQ(t.pins().size(), 1u);
}

TEST(Tuner, WatchAndDisplace) {
  Tuner t(small_plane());
  t.watch(3);
  EXPECT_EQ(t.session().watched(), 3);
  t.watch(-1);
  t.watch(100000);
  EXPECT_EQ(t.session().watched(), 3);
  const Vec3 before = t.session().state().x[3];
  t.displace(3, Vec3(0, 1.5, 0));
  EXPECT_DOUBLE_EQ(t.session().state().x[3].y(), before.y() + 1.5);
  t.displace(3, Vec3(std::numeric_limits<double>::infinity(), 0, 0));  // refused
  EXPECT_TRUE(t.session().state().x[3].allFinite());
  t.step(1);
  EXPECT_GT(t.session().trace().back().watched.displacement, 1.0);
}

TEST(Tuner, TheScenesOwnCutChangesTheTopology) {
  // A cut scripted in the scene happens inside a step: the mesh view's index buffer and the
  // cached exact analysis are keyed on topology(), so it must change then too.
  SceneSpec s = small_plane();
  s.cuts.push_back({4, {2.6, -1}, {2.6, 10}});  // along x = 2.6 cm after 4 steps
  Tuner t(s);
  t.criteria_state().set_slow_threshold(1e9);  // counts analyses: no throttle, however slow
  const int springs = t.session().model().spec().spring_count();
  ASSERT_NE(t.exact(), nullptr);
  const int runs = t.criteria_state().exact_runs();
  const auto topo = t.topology();
  t.step(4);
  EXPECT_EQ(t.topology(), topo);  // no cut yet
  t.step(1);
  EXPECT_LT(t.session().model().spec().spring_count(), springs);
  EXPECT_NE(t.topology(), topo);
  ASSERT_NE(t.exact(), nullptr);
  EXPECT_EQ(t.criteria_state().exact_runs(), runs + 1);  // analysed again, on the cut mesh
}

TEST(Tuner, CutWithTheScreenToolWhileRunningAndTheBoundsReact) {
  Tuner t(small_plane());
  Tuner twin(small_plane());
  t.step(3);
  twin.step(3);
  // Look down on the mesh and drag a line across the middle, as the mesh view does.
  OrbitCamera cam;
  Vec3f lo, hi;
  bounding_box(t.session().model().spec().rest, lo, hi);
  cam.fit(lo, hi);
  cam.pitch = 1.2f;
  const Viewport vp{0, 0, 800, 600};
  const Mat4f m = cam.view_projection(vp.aspect());
  const auto pts = project_points(m, vp, t.session().state().x);
  const float mid = 0.5f * (lo.x() + hi.x()) + 0.1f;
  const ScreenPoint a = project(m, vp, Vec3f(mid, 0, lo.z() - 1));
  const ScreenPoint b = project(m, vp, Vec3f(mid, 0, hi.z() + 1));
  const auto springs =
      springs_crossing_screen(t.session().model(), pts, Vec2f(a.x, a.y), Vec2f(b.x, b.y));
  const int before = t.session().model().spec().spring_count();
  const auto topo = t.topology();
  ASSERT_GT(springs.size(), 5u);
  EXPECT_EQ(t.cut(springs), static_cast<int>(springs.size()));
  EXPECT_EQ(t.session().model().spec().spring_count(), before - static_cast<int>(springs.size()));
  EXPECT_NE(t.topology(), topo);
  EXPECT_EQ(t.session().springs_cut(), static_cast<int>(springs.size()));
  // Next step: the forces changed, so the upper bound (eq. 6) of the watched node changes.
  t.step(1);
  twin.step(1);
  EXPECT_EQ(t.session().trace().size(), 4u);
  EXPECT_NE(t.session().trace().back().watched.upper, twin.session().trace().back().watched.upper);
  // A reset brings the springs back.
  t.reset();
  EXPECT_EQ(t.session().model().spec().spring_count(), before);
}

TEST(Tuner, ReducedTraceFollowsTheSession) {
  Tuner t(small_plane());
  t.step(20);
  EXPECT_EQ(t.reduced_trace().size(), 20u);
  const auto gen = t.generation();
  t.reset();
  EXPECT_NE(t.generation(), gen);
  EXPECT_TRUE(t.reduced_trace().empty());
}

TEST(Tuner, ExactDampingLimitIsPositiveAndCached) {
  Tuner t(small_plane());
  const auto g = t.exact_gamma_max();
  ASSERT_TRUE(g.has_value());
  EXPECT_GT(*g, 0.0);
  EXPECT_LT(*g, 2 * t.params().m / t.params().dt);  // gamma < 2m/dt - m lambda dt / 2
  EXPECT_EQ(t.exact_gamma_max(), g);
}

TEST(Tuner, OpenSceneFailureKeepsTheCurrentScene) {
  Tuner t(small_plane());
  std::string err;
  EXPECT_FALSE(t.open_scene("/nonexistent/scene.toml", &err));
  EXPECT_NE(err.find("/nonexistent/scene.toml"), std::string::npos);
  EXPECT_EQ(t.scene().name, "small-plane");
  EXPECT_TRUE(t.open_scene(DAMPBOUND_SOURCE_DIR "/scenes/two-node.toml", &err)) << err;
  EXPECT_NE(t.scene().name, "small-plane");
}

TEST(Tuner, ASceneSwitchDropsTheLastScenesAnalysis) {
  // The criteria's exact analysis on show is the new scene's, never the old one's while the
  // new one is computed.
  Tuner t(small_plane());
  ASSERT_NE(t.exact(), nullptr);
  const double old_lambda = t.exact()->spectrum.lambda_max;
  ASSERT_NE(t.criteria_state().shown(), nullptr);
  std::string err;
  ASSERT_TRUE(t.open_scene(DAMPBOUND_SOURCE_DIR "/scenes/two-node.toml", &err)) << err;
  EXPECT_EQ(t.criteria_state().shown(), nullptr);
  ASSERT_NE(t.exact(), nullptr);
  EXPECT_NE(t.exact()->spectrum.lambda_max, old_lambda);
}

TEST(TunerText, NeverNaN) {
  EXPECT_EQ(fmt(std::numeric_limits<double>::quiet_NaN()), "-");
  EXPECT_EQ(fmt(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(fmt(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(fmt(0.002), "0.002");
  RunResult r;
  EXPECT_EQ(verdict_short(r), "running");
  r.outcome = Outcome::diverged;
  r.iterations = 45;
  EXPECT_EQ(verdict_short(r), "diverged at 45");
  r.outcome = Outcome::restored;
  EXPECT_EQ(verdict_short(r), "restored at 45");
  r.outcome = Outcome::settled;
  r.settled_at = 40;
  EXPECT_EQ(verdict_short(r), "settled at 40");
  r.outcome = Outcome::not_settled;
  r.iterations = 1000;
  r.first_entry = 12;
  r.left_at = 63;
  EXPECT_EQ(verdict_short(r), "not settled at 1000 (entered at 12, left at 63)");
}

}  // namespace
}  // namespace dampbound::ui
