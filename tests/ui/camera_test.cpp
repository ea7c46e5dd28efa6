// The mesh view's orbit camera (ui/camera.hpp): projection, orbit, pan, zoom, fit and the
// view-plane drag offset. Pure maths, no GL.
#include "ui/camera.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace dampbound::ui {
namespace {

const Viewport kVp{100.0f, 50.0f, 800.0f, 600.0f};

TEST(Camera, TargetProjectsToTheViewportCentre) {
  OrbitCamera c;
  c.target = Vec3f(3, 1, -2);
  const ScreenPoint p = project(c.view_projection(kVp.aspect()), kVp, c.target);
  ASSERT_TRUE(p.visible);
  EXPECT_NEAR(p.x, 500.0f, 1e-3f);
  EXPECT_NEAR(p.y, 350.0f, 1e-3f);
  EXPECT_NEAR(p.depth, c.distance, 1e-3f);
}

TEST(Camera, BasisIsOrthonormalAndUpIsUpOnScreen) {
  OrbitCamera c;
  c.yaw = 0.3f;
  c.pitch = 0.4f;
  EXPECT_NEAR(c.forward().norm(), 1.0f, 1e-5f);
  EXPECT_NEAR(c.right().dot(c.up()), 0.0f, 1e-5f);
  EXPECT_NEAR(c.forward().dot(c.up()), 0.0f, 1e-5f);
  EXPECT_GT(c.up().y(), 0.0f);
  // A point above the target (world +y) appears above the centre (smaller screen y).
  const ScreenPoint p = project(c.view_projection(kVp.aspect()), kVp, c.target + Vec3f(0, 1, 0));
  EXPECT_LT(p.y, 350.0f);
  // A point to the camera's right appears right of the centre.
  const ScreenPoint q = project(c.view_projection(kVp.aspect()), kVp, c.target + c.right());
  EXPECT_GT(q.x, 500.0f);
}

TEST(Camera, PointsBehindTheEyeAreNotVisible) {
  OrbitCamera c;
  const Mat4f m = c.view_projection(kVp.aspect());
  EXPECT_FALSE(project(m, kVp, c.eye() - 5.0f * c.forward()).visible);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(project(m, kVp, Vec3f(nan, 0, 0)).visible);
}

TEST(Camera, OrbitKeepsDistanceAndClampsPitch) {
  OrbitCamera c;
  c.target = Vec3f(1, 2, 3);
  const float d0 = (c.eye() - c.target).norm();
  c.orbit(120.0f, 30.0f);
  EXPECT_NEAR((c.eye() - c.target).norm(), d0, 1e-3f);
  c.orbit(0.0f, 1e5f);
  EXPECT_LE(c.pitch, 1.55f);
  c.orbit(0.0f, -1e5f);
  EXPECT_GE(c.pitch, -1.55f);
}

TEST(Camera, ZoomScalesDistanceAndClamps) {
  OrbitCamera c;
  c.distance = 10.0f;
  c.zoom(1.0f);
  EXPECT_NEAR(c.distance, 9.0f, 1e-4f);
  c.zoom(-2.0f);
  EXPECT_NEAR(c.distance, 9.0f / 0.81f, 1e-3f);
  c.zoom(1e4f);
  EXPECT_GE(c.distance, 1e-3f);
}

TEST(Camera, ViewPlaneOffsetMovesAPointByThosePixels) {
  OrbitCamera c;
  c.yaw = 1.1f;
  c.pitch = 0.5f;
  const Mat4f m = c.view_projection(kVp.aspect());
  const Vec3f p = c.target + Vec3f(0.5f, 0.2f, -0.3f);
  const ScreenPoint a = project(m, kVp, p);
  const Vec3f off = c.view_plane_offset(12.0f, -7.0f, a.depth, kVp.h);
  EXPECT_NEAR(off.dot(c.forward()), 0.0f, 1e-5f);  // stays in the view plane
  const ScreenPoint b = project(m, kVp, p + off);
  EXPECT_NEAR(b.x - a.x, 12.0f, 0.05f);
  EXPECT_NEAR(b.y - a.y, -7.0f, 0.05f);
}

TEST(Camera, PanMovesTheSceneWithTheMouse) {
  OrbitCamera c;
  const Vec3f world(0.0f, 0.0f, 0.0f);
  const ScreenPoint a = project(c.view_projection(kVp.aspect()), kVp, world);
  c.pan(20.0f, 10.0f, kVp.h);
  const ScreenPoint b = project(c.view_projection(kVp.aspect()), kVp, world);
  EXPECT_NEAR(b.x - a.x, 20.0f, 0.5f);
  EXPECT_NEAR(b.y - a.y, 10.0f, 0.5f);
}

TEST(Camera, FitShowsTheWholeBox) {
  OrbitCamera c;
  const Vec3f lo(0, -1, 0), hi(20, 5, 20);
  c.fit(lo, hi);
  const Mat4f m = c.view_projection(kVp.aspect());
  for (int i = 0; i < 8; ++i) {
    const Vec3f corner((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(),
                       (i & 4) ? hi.z() : lo.z());
    const ScreenPoint p = project(m, kVp, corner);
    ASSERT_TRUE(p.visible);
    EXPECT_GE(p.x, kVp.x);
    EXPECT_LE(p.x, kVp.x + kVp.w);
    EXPECT_GE(p.y, kVp.y);
    EXPECT_LE(p.y, kVp.y + kVp.h);
  }
}

}  // namespace
}  // namespace dampbound::ui
