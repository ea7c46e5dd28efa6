// The tuner window's layout without ImGui (ui/gui_layout.hpp): the default panels tile every
// supported window size, the compact threshold, and where panels go on a resize.
#include "ui/gui_layout.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace dampbound::ui {
namespace {

float area(const PanelRect& r) {
  return r.w * r.h;
}

bool overlap(const PanelRect& a, const PanelRect& b) {
  return a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
}

TEST(GuiLayout, DefaultPanelsTileTheWindow) {
  for (const auto& [W, H] : std::vector<std::pair<float, float>>{
           {1024, 640}, {1280, 800}, {1600, 1000}, {1920, 1080}, {2560, 1440}}) {
    SCOPED_TRACE(std::to_string(W) + " x " + std::to_string(H));
    const std::vector<PanelRect> panels = default_layout(W, H);
    ASSERT_EQ(panels.size(), 6u);
    float covered = 0;
    for (size_t i = 0; i < panels.size(); ++i) {
      const PanelRect& p = panels[i];
      EXPECT_GE(p.x, 0) << p.name;
      EXPECT_GE(p.y, 0) << p.name;
      EXPECT_LE(p.x + p.w, W) << p.name;
      EXPECT_LE(p.y + p.h, H) << p.name;
      covered += area(p);
      for (size_t j = 0; j < i; ++j) {
        if (area(p) > 0 && area(panels[j]) > 0) {
          EXPECT_FALSE(overlap(p, panels[j])) << p.name << " / " << panels[j].name;
        }
      }
    }
    EXPECT_FLOAT_EQ(covered, W * H);  // no gap either
    // The left column: 24.5 % of the width, within 330..430 px.
    EXPECT_GE(panels[0].w, 330);
    EXPECT_LE(panels[0].w, 430);
  }
}

TEST(GuiLayout, CompactBelow900PixelsGivesTheParametersTheColumn) {
  EXPECT_TRUE(compact_layout(899));
  EXPECT_FALSE(compact_layout(kCompactLayoutHeight));
  const std::vector<PanelRect> small = default_layout(1024, 640);
  EXPECT_EQ(small[0].name, "Parameters");
  EXPECT_FLOAT_EQ(small[0].h, 640);
  EXPECT_EQ(small[1].name, "Status");
  EXPECT_FLOAT_EQ(small[1].h, 0);
  const std::vector<PanelRect> large = default_layout(1600, 1000);
  EXPECT_FLOAT_EQ(large[0].h + large[1].h, 1000);
  EXPECT_GT(large[1].h, 300);
}

TEST(GuiLayout, DefaultPanelsFollowAResizeMovedOnesScale) {
  std::vector<PanelRect> drawn = default_layout(1280, 800);
  drawn[3] = {"Damping bounds", 640, 100, 400, 300};  // moved and resized by the user
  const std::vector<PanelRect> after = panels_after_resize(drawn, 1280, 800, 960, 600);
  const std::vector<PanelRect> fresh = default_layout(960, 600);
  ASSERT_EQ(after.size(), drawn.size());
  for (size_t i = 0; i < after.size(); ++i) {
    if (i == 3) continue;
    EXPECT_EQ(after[i].name, fresh[i].name);
    EXPECT_FLOAT_EQ(after[i].x, fresh[i].x) << after[i].name;
    EXPECT_FLOAT_EQ(after[i].w, fresh[i].w) << after[i].name;
    EXPECT_FLOAT_EQ(after[i].h, fresh[i].h) << after[i].name;
  }
  EXPECT_FLOAT_EQ(after[3].x, 480);
  EXPECT_FLOAT_EQ(after[3].y, 75);
  EXPECT_FLOAT_EQ(after[3].w, 300);
  EXPECT_FLOAT_EQ(after[3].h, 225);
}

TEST(GuiLayout, NothingDrawnBeforeTheFirstFrame) {
  GuiLayout layout;
  layout.update(1024, 640);
  EXPECT_TRUE(layout.compact());
  EXPECT_FALSE(layout.drawn("Parameters"));
  layout.update(1600, 1000);
  EXPECT_FALSE(layout.compact());
}

TEST(GuiLayout, RememberedPanelsComeFromImguiIni) {
  const std::string ini =
      "[Window][Debug##Default]\nPos=60,60\nSize=400,400\nCollapsed=0\n\n"
      "[Window][Mesh view]\r\nPos=392,0\r\nSize=579,1232\r\n\n"
      "[Window][No size]\nPos=1,2\n\n"
      "[Window][Bad]\nPos=x,2\nSize=3,4\n\n"
      "[Window][Zero]\nPos=1,2\nSize=0,4\n\n"
      "[Table][0x1234,4]\nPos=1,2\nSize=3,4\n"
      "[Window][Debug##Default]\nPos=7,8\nSize=9,10\n";
  const std::vector<PanelRect> r = remembered_panels(ini);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].name, "Debug##Default");
  EXPECT_EQ(r[0].x, 7);  // the later section
  EXPECT_EQ(r[1].name, "Mesh view");
  EXPECT_EQ(r[1].x, 392);
  EXPECT_EQ(r[1].y, 0);
  EXPECT_EQ(r[1].w, 579);
  EXPECT_EQ(r[1].h, 1232);
  EXPECT_TRUE(remembered_panels("").empty());
}

}  // namespace
}  // namespace dampbound::ui
