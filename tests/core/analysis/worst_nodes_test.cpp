// The nodes that limit dt and gamma (core/analysis/worst_nodes.cpp): the planted bad node comes
// first, with its cause in words and its local facts.
#include "core/analysis/worst_nodes.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "dampbound/run/scene.hpp"

namespace dampbound {
namespace {

ModelSpec grid5() { return make_grid(GridSpec{5, 5, 0.57, true, true}); }

TEST(WorstNodes, ALightNodeComesFirstAndIsNamedForItsMass) {
  ModelSpec s = grid5();
  s.mass_scale[12] = 0.01;
  Params p;
  const Model model = compile_model(s, p);
  const WorstNodes w = worst_nodes(model, model.spec().rest, p.dt, 3);
  ASSERT_EQ(w.by_dt.size(), 3u);
  ASSERT_EQ(w.by_gamma.size(), 3u);
  EXPECT_EQ(w.by_dt[0].node, 12);
  EXPECT_EQ(w.by_gamma[0].node, 12);
  EXPECT_EQ(w.by_dt[0].cause, "mass 1e+02x below the median");
  EXPECT_DOUBLE_EQ(w.by_dt[0].mass, model.mass[12]);
  EXPECT_EQ(w.by_dt[0].degree, model.incident_offset[13] - model.incident_offset[12]);
  EXPECT_LE(w.by_dt[0].dt_safe, w.by_dt[1].dt_safe);
  EXPECT_LE(w.by_dt[1].dt_safe, w.by_dt[2].dt_safe);
  EXPECT_LE(w.by_gamma[0].gamma_safe, w.by_gamma[1].gamma_safe);
  EXPECT_DOUBLE_EQ(w.median_edge, 0.57);
}

TEST(WorstNodes, AShortEdgeIsNamedAndTheCountIsClamped) {
  ModelSpec s = grid5();
  // Node 12 moved next to node 13: its edge to 13 is about 10x shorter than the median.
  s.rest[12] = s.rest[13] + (s.rest[12] - s.rest[13]) * 0.1;
  Params p;
  const Model model = compile_model(s, p);
  const WorstNodes w = worst_nodes(model, model.spec().rest, p.dt, 1000);
  EXPECT_EQ(w.by_dt.size(), 25u);  // every free node, no more
  const WorstNode& first = w.by_dt[0];
  EXPECT_TRUE(first.node == 12 || first.node == 13) << first.node;
  EXPECT_EQ(first.cause.rfind("edge ", 0), 0u) << first.cause;
  EXPECT_NEAR(first.shortest_edge, 0.057, 1e-12);
  EXPECT_TRUE(worst_nodes(model, model.spec().rest, p.dt, 0).by_dt.empty());
  EXPECT_TRUE(worst_nodes(model, model.spec().rest, p.dt, -3).by_gamma.empty());
}

}  // namespace
}  // namespace dampbound
