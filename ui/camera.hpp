#pragma once
// The mesh view's orbit camera: pure maths (no GL, no ImGui context), unit-tested in
// tests/ui/camera_test.cpp. World units are the model's centimetres; screen coordinates are
// pixels with y growing downwards, as ImGui's.
#include <Eigen/Core>

namespace dampbound::ui {

using Vec2f = Eigen::Vector2f;
using Vec3f = Eigen::Vector3f;
using Mat4f = Eigen::Matrix4f;

/// A rectangle of the screen in pixels (top-left corner and size), where the view is drawn.
struct Viewport {
  float x = 0.0f, y = 0.0f;  ///< top-left corner (pixels)
  float w = 1.0f, h = 1.0f;  ///< size (pixels, > 0)
  float aspect() const { return w / h; }
};

/// A point projected to the screen: pixel position and eye-space depth (distance along the
/// view direction, cm). `visible` is false behind the camera or for non-finite input.
struct ScreenPoint {
  float x = 0.0f, y = 0.0f;
  float depth = 0.0f;
  bool visible = false;
};

/// Looks at `target` from `distance` away; yaw turns about the world y axis, pitch lifts the
/// eye above the xz-plane (the paper's mesh lies in the xz-plane and is perturbed along y).
struct OrbitCamera {
  Vec3f target = Vec3f::Zero();
  float yaw = 0.75f;       ///< radians about +y
  float pitch = 0.6f;      ///< radians above the xz-plane, kept inside (-1.55, 1.55)
  float distance = 30.0f;  ///< cm from target to eye, > 0
  float fov_y = 0.7f;      ///< vertical field of view (radians)

  /// Eye position in world coordinates.
  Vec3f eye() const;
  /// Unit vectors of the camera: forward (eye to target), right and up on the screen.
  Vec3f forward() const;
  Vec3f right() const;
  Vec3f up() const;

  /// World -> eye transform (right-handed, looking down -z).
  Mat4f view() const;
  /// Perspective projection (OpenGL clip space); near and far follow the distance.
  Mat4f projection(float aspect) const;
  /// projection(aspect) * view().
  Mat4f view_projection(float aspect) const;

  /// Turns the camera by a mouse drag of (dx, dy) pixels (0.01 rad per pixel).
  void orbit(float dx_px, float dy_px);
  /// Moves the target in the view plane so the scene follows a drag of (dx, dy) pixels in a
  /// viewport `viewport_h` pixels high.
  void pan(float dx_px, float dy_px, float viewport_h);
  /// Wheel steps: positive zooms in (distance x 0.9 per step), clamped to [1e-3, 1e6] cm.
  void zoom(float wheel_steps);
  /// Frames the box [lo, hi]: target at its centre, distance so the box fits the view.
  void fit(const Vec3f& lo, const Vec3f& hi);
  /// Like fit(), then moves in as far as every corner of the box stays inside the view of
  /// the given aspect ratio with `margin` (fraction of the half-size) to spare.
  void fit_tight(const Vec3f& lo, const Vec3f& hi, float aspect, float margin = 0.06f);

  /// World size (cm) of one screen pixel at eye-space depth `depth` in a viewport
  /// `viewport_h` pixels high.
  float pixel_size_at(float depth, float viewport_h) const;
  /// World offset that moves a point at eye-space `depth` by (dx, dy) pixels on the screen,
  /// within the view plane (what dragging a node does).
  Vec3f view_plane_offset(float dx_px, float dy_px, float depth, float viewport_h) const;
};

/// Projects a world point with `view_proj` into `vp`.
ScreenPoint project(const Mat4f& view_proj, const Viewport& vp, const Vec3f& p);

}  // namespace dampbound::ui
