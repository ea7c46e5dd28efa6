// The stability map as data: panels, cells and the boundaries of the paper and of SPEC 7.
#include "core/sweep/map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/sweep/setup.hpp"
#include "core/sweep/summary.hpp"
#include "core/sweep/trials.hpp"
#include "dampbound/physics/error.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

SweepTable small_table(const SceneSpec& scene, DampingPolicy policy) {
  const SweepSpec s = test::small_sweep(scene, 150, policy);
  const SweepGrid grid(s);
  const TrialClasses classes = find_classes(grid, similarity_unavailable(scene));
  std::vector<TrialParams> reps;
  for (std::uint64_t t : classes.representative) reps.push_back(grid.params(t));
  SweepTable t;
  t.header.scene_name = scene.name;
  t.header.definition = sweep_definition(s);
  t.header.policy = policy;
  t.header.trials = grid.trials();
  t.rows = sweep_rows(grid, classes, run_batched(scene, policy, s.rules, reps), 1, 1);
  return t;
}

TEST(SweepMap, FixedPolicyMapHasCellsForEveryTrialAndTheExactLimit) {
  const SceneSpec scene = test::shipped_scene("two-node");
  const SweepTable t = small_table(scene, DampingPolicy::fixed);
  const StabilityMap map = build_stability_map(t, unit_stiffness_eigenvalue(scene));
  EXPECT_EQ(map.max_iterations, 150);
  EXPECT_NE(map.title.find("policy fixed"), std::string::npos) << map.title;
  EXPECT_EQ(map.rule, StopRule::first_entry);
  EXPECT_EQ(map.summary, summary_lines(t.rows, DampingPolicy::fixed, unit_stiffness_eigenvalue(scene)));
  ASSERT_GE(map.panels.size(), 2u);
  bool exact = false;
  for (const MapPanel& p : map.panels) {
    ASSERT_GE(p.x_edges.size(), 2u);
    ASSERT_GE(p.y_edges.size(), 2u);
    EXPECT_EQ(p.cells.size(), (p.x_edges.size() - 1) * (p.y_edges.size() - 1));
    EXPECT_EQ(p.iterations.size(), p.cells.size());
    int filled = 0;
    for (MapCell c : p.cells) filled += c != MapCell::empty;
    EXPECT_GT(filled, 0);
    for (const MapLine& l : p.lines) exact |= l.kind == MapLineKind::exact_linear;
  }
  EXPECT_TRUE(exact);
  // Without lambda_max: no exact lines.
  for (const MapPanel& p : build_stability_map(t, std::nan("")).panels)
    for (const MapLine& l : p.lines) EXPECT_NE(l.kind, MapLineKind::exact_linear);
}

TEST(SweepMap, RefusesAnEmptySweepAndAMissingDt) {
  const SceneSpec scene = test::shipped_scene("two-node");
  SweepTable t = small_table(scene, DampingPolicy::fixed);
  MapOptions o;
  o.dt = 0.5;
  EXPECT_THROW(build_stability_map(t, 1.0, o), InputError);
  t.rows.clear();
  EXPECT_THROW(build_stability_map(t, 1.0), InputError);
}

TEST(SweepMap, UpperPolicyMapsTheFactor) {
  const SceneSpec scene = test::shipped_scene("two-node");
  const SweepTable t = small_table(scene, DampingPolicy::upper);
  const StabilityMap map = build_stability_map(t, unit_stiffness_eigenvalue(scene));
  ASSERT_FALSE(map.panels.empty());
  EXPECT_NE(map.title.find("policy upper"), std::string::npos);
  EXPECT_NE(map.panels[0].y_label.find("factor"), std::string::npos) << map.panels[0].y_label;
}

}  // namespace
}  // namespace dampbound
