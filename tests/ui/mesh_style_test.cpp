// The mesh view's colours: SPEC 9's "not guaranteed" beside the node states of the paper's
// bounds (ui/mesh_style.cpp).
#include "ui/mesh_style.hpp"

#include <gtest/gtest.h>

namespace dampbound::ui {
namespace {

TEST(MeshStyle, MultisamplingOnlyWhereItPays) {
  EXPECT_EQ(mesh_samples(8.0f, 100, false), 1);  // lines far apart: no moire
  EXPECT_EQ(mesh_samples(3.0f, 100, true), 4);   // small dense mesh: always smooth
  EXPECT_EQ(mesh_samples(3.0f, kBigMeshSprings + 1, false), 4);  // paused
  EXPECT_EQ(mesh_samples(3.0f, kBigMeshSprings + 1, true), 1);   // playing
}

TEST(MeshStyle, SpringsFadeWithTheirSpacingAndABigMeshLeavesTheFaintestOutWhilePlaying) {
  EXPECT_EQ(spring_alpha(6.0f), 1.0f);
  EXPECT_GT(spring_alpha(3.0f), kFaintestSprings);
  EXPECT_LT(spring_alpha(3.0f), 1.0f);
  EXPECT_EQ(spring_alpha(2.0f), kFaintestSprings);
  EXPECT_EQ(spring_alpha(0.5f), kFaintestSprings);
  const size_t big = kBigMeshSprings + 1;
  EXPECT_FALSE(springs_drawn(true, 2.0f, big, true));   // faintest, big, playing: left out
  EXPECT_TRUE(springs_drawn(true, 2.0f, big, false));   // paused
  EXPECT_TRUE(springs_drawn(true, 3.0f, big, true));    // zoomed in: apart enough to see
  EXPECT_TRUE(springs_drawn(true, 2.0f, 100, true));    // a small mesh costs little
  EXPECT_FALSE(springs_drawn(false, 8.0f, 100, false)); // the user hid them
}

TEST(MeshStyle, NotGuaranteedNodesGetTheirOwnColourUnlessThePaperRaisesItsAlarm) {
  EXPECT_NE(unguaranteed_color(), status_color(NodeStatus::within));
  for (NodeStatus s : {NodeStatus::within, NodeStatus::clamped, NodeStatus::violating,
                       NodeStatus::unstabilisable, NodeStatus::fixed}) {
    EXPECT_NE(unguaranteed_color(), status_color(s)) << status_label(s);
    EXPECT_EQ(node_color(s, false), status_color(s)) << status_label(s);
  }
  // Within, clamped and (what the safe policy's damping at gamma_safe < gamma_lo is)
  // violating show SPEC 9's colour; unstabilisable and fixed keep theirs.
  EXPECT_EQ(node_color(NodeStatus::within, true), unguaranteed_color());
  EXPECT_EQ(node_color(NodeStatus::clamped, true), unguaranteed_color());
  EXPECT_EQ(node_color(NodeStatus::violating, true), unguaranteed_color());
  EXPECT_EQ(node_color(NodeStatus::unstabilisable, true),
            status_color(NodeStatus::unstabilisable));
  EXPECT_EQ(node_color(NodeStatus::fixed, true), status_color(NodeStatus::fixed));
  EXPECT_STRNE(unguaranteed_label(), "");
  EXPECT_STRNE(unguaranteed_help(), "");
}

TEST(MeshStyle, ShadeRunsFromGreyThroughVioletToYellow) {
  EXPECT_EQ(shade_color(0.0f), IM_COL32(90, 95, 105, 255));  // nothing added
  EXPECT_EQ(shade_color(-1.0f), shade_color(0.0f));
  EXPECT_EQ(shade_color(1.0f), IM_COL32(255, 220, 60, 255));
  EXPECT_EQ(shade_color(2.0f), shade_color(1.0f));
  EXPECT_EQ(shade_color(0.5f), IM_COL32(220, 70, 160, 255));
  EXPECT_NE(shade_color(1e-6f), shade_color(0.0f));  // any added mass stands out
}

}  // namespace
}  // namespace dampbound::ui
