// Screen-space picking and the cut tool's geometry (ui/mesh_pick.hpp), no GL.
#include "ui/mesh_pick.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "dampbound/run/scene.hpp"

namespace dampbound::ui {
namespace {

TEST(SegmentsIntersect, CrossingParallelTouchingCollinear) {
  const Vec2f o(0, 0), x(10, 0), y(0, 10), xy(10, 10);
  EXPECT_TRUE(segments_intersect(o, xy, Vec2f(0, 10), Vec2f(10, 0)));  // an X
  EXPECT_FALSE(segments_intersect(o, x, Vec2f(0, 1), Vec2f(10, 1)));   // parallel
  EXPECT_TRUE(segments_intersect(o, x, Vec2f(5, 0), Vec2f(5, 5)));     // T: touching
  EXPECT_TRUE(segments_intersect(o, x, x, xy));                        // shared end
  EXPECT_TRUE(segments_intersect(o, x, Vec2f(5, 0), Vec2f(15, 0)));    // collinear overlap
  EXPECT_FALSE(segments_intersect(o, x, Vec2f(11, 0), Vec2f(15, 0)));  // collinear apart
  EXPECT_FALSE(segments_intersect(o, y, Vec2f(1, 5), Vec2f(3, 5)));    // short of it
  EXPECT_TRUE(segments_intersect(o, x, Vec2f(3, 0), Vec2f(3, 0)));     // a point on it
  EXPECT_FALSE(segments_intersect(o, x, Vec2f(3, 1), Vec2f(3, 1)));    // a point off it
}

TEST(PickNode, NearestWithinRadiusAndFrontMostOnTies) {
  std::vector<ScreenPoint> pts(4);
  pts[0] = {100, 100, 5, true};
  pts[1] = {110, 100, 5, true};
  pts[2] = {104, 100, 9, true};   // nearer on screen but... see below
  pts[3] = {103, 100, 1, false};  // behind the camera: never picked
  EXPECT_EQ(pick_node(pts, 103, 100, 8), 2);
  EXPECT_EQ(pick_node(pts, 109, 100, 8), 1);
  EXPECT_EQ(pick_node(pts, 200, 200, 8), -1);
  // Two nodes at the same screen spot: the one nearer the camera wins.
  pts[1] = {104, 100.2f, 3, true};
  EXPECT_EQ(pick_node(pts, 104, 100, 8), 1);
  EXPECT_EQ(pick_node({}, 0, 0, 8), -1);
}

/// A camera looking down on the rest plane of a grid, from an angle.
struct TopView {
  OrbitCamera cam;
  Viewport vp{0, 0, 900, 700};
  Mat4f m;
  explicit TopView(const ModelSpec& model) {
    Vec3f lo, hi;
    bounding_box(model.rest, lo, hi);
    cam.fit(lo, hi);
    cam.yaw = 0.4f;
    cam.pitch = 1.1f;
    m = cam.view_projection(vp.aspect());
  }
  Vec2f at(double x, double z) const {
    const ScreenPoint p = project(m, vp, Vec3f(static_cast<float>(x), 0, static_cast<float>(z)));
    return Vec2f(p.x, p.y);
  }
};

TEST(SpringsCrossingScreen, MatchesTheCoreCutOfThePlane) {
  // The projection of a plane is a projective map: a segment drawn on the screen over the
  // mesh cuts exactly the springs that the same segment cuts in the plane (core's cut).
  GridSpec g;
  g.nx = g.nz = 12;
  g.spacing = 1.0;
  const ModelSpec model = make_grid(g);
  const TopView v(model);
  const auto pts = project_points(v.m, v.vp, model.rest);
  const double cuts[3][4] = {{5.5, -1, 5.5, 12}, {-1, 2.3, 8.7, 9.1}, {2.2, 3.3, 7.7, 4.4}};
  for (const auto& c : cuts) {
    const double from[2] = {c[0], c[1]}, to[2] = {c[2], c[3]};
    std::vector<int> want = springs_crossing(model, model.rest, from, to);
    std::vector<int> got = springs_crossing_screen(model, pts, v.at(c[0], c[1]), v.at(c[2], c[3]));
    ASSERT_FALSE(want.empty());
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(got, want) << "cut " << c[0] << "," << c[1] << " -> " << c[2] << "," << c[3];
  }
}

TEST(SpringsCrossingScreen, SkipsSpringsBehindTheCameraAndShortLines) {
  ModelSpec model;
  add_node(model, Vec3(0, 0, 0));
  add_node(model, Vec3(1, 0, 0));
  add_spring(model, 0, 1);
  std::vector<ScreenPoint> pts = {{0, 0, 1, true}, {10, 0, 1, true}};
  EXPECT_EQ(springs_crossing_screen(model, pts, Vec2f(5, -5), Vec2f(5, 5)), std::vector<int>{0});
  EXPECT_TRUE(springs_crossing_screen(model, pts, Vec2f(5, 1), Vec2f(5, 5)).empty());
  pts[1].visible = false;
  EXPECT_TRUE(springs_crossing_screen(model, pts, Vec2f(5, -5), Vec2f(5, 5)).empty());
}

TEST(BoundingBox, IgnoresNonFinitePositions) {
  const double inf = std::numeric_limits<double>::infinity();
  Vec3f lo, hi;
  EXPECT_FALSE(bounding_box({}, lo, hi));
  ASSERT_TRUE(bounding_box({Vec3(1, 2, 3), Vec3(inf, 0, 0), Vec3(-1, 5, 0)}, lo, hi));
  EXPECT_EQ(lo, Vec3f(-1, 2, 0));
  EXPECT_EQ(hi, Vec3f(1, 5, 3));
}

}  // namespace
}  // namespace dampbound::ui
