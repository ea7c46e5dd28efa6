// The Worst nodes tab's list (ui/tuner_worst.hpp): core's worst_nodes() at rest, computed
// again when the parameters or the springs change, and only then.
#include "ui/tuner_worst.hpp"

#include <gtest/gtest.h>

#include "core/io/scene_file.hpp"
#include "ui/tuner.hpp"

namespace dampbound::ui {
namespace {

void expect_same(const std::vector<WorstNode>& a, const std::vector<WorstNode>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].node, b[k].node);
    EXPECT_EQ(a[k].dt_safe, b[k].dt_safe);
    EXPECT_EQ(a[k].gamma_safe, b[k].gamma_safe);
    EXPECT_EQ(a[k].cause, b[k].cause);
  }
}

TEST(TunerWorst, ListsCoresWorstNodesAtRestAndFollowsChanges) {
  Tuner t(load_scene(DAMPBOUND_SOURCE_DIR "/scenes/stiff-region.toml"));
  t.step(5);  // the list is of the rest state, as `bounds --worst`
  TunerWorst w;
  const WorstNodes& got = w.get(t.session(), t.topology(), 7);
  const Model& m = t.session().model();
  const WorstNodes want = worst_nodes(m, m.spec().rest, t.params().dt, 7);
  ASSERT_EQ(got.by_dt.size(), 7u);
  expect_same(got.by_dt, want.by_dt);
  expect_same(got.by_gamma, want.by_gamma);
  EXPECT_FALSE(got.by_dt.front().cause.empty());
  w.get(t.session(), t.topology(), 7);
  t.step(1);
  w.get(t.session(), t.topology(), 7);
  EXPECT_EQ(w.computations(), 1);  // steps do not move the rest state
  Params p = t.params();
  p.dt *= 0.5;
  ASSERT_TRUE(t.set_params(p));
  const WorstNodes& again = w.get(t.session(), t.topology(), 7);
  EXPECT_EQ(w.computations(), 2);
  expect_same(again.by_gamma, worst_nodes(m, m.spec().rest, p.dt, 7).by_gamma);
  t.cut({0, 1, 2});
  w.get(t.session(), t.topology(), 7);
  EXPECT_EQ(w.computations(), 3);
  w.get(t.session(), t.topology(), 3);
  EXPECT_EQ(w.computations(), 4);
}

}  // namespace
}  // namespace dampbound::ui
