#include "ui/camera.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace dampbound::ui {

Vec3f OrbitCamera::forward() const {
  // The eye sits at target - distance * forward.
  const float cp = std::cos(pitch), sp = std::sin(pitch);
  return Vec3f(-cp * std::cos(yaw), -sp, -cp * std::sin(yaw));
}

Vec3f OrbitCamera::eye() const {
  return target - distance * forward();
}

Vec3f OrbitCamera::right() const {
  const Vec3f r = forward().cross(Vec3f::UnitY());
  const float n = r.norm();
  return n > 1e-6f ? Vec3f(r / n) : Vec3f::UnitX();
}

Vec3f OrbitCamera::up() const {
  return right().cross(forward());
}

Mat4f OrbitCamera::view() const {
  const Vec3f f = forward(), r = right(), u = up(), e = eye();
  Mat4f m = Mat4f::Identity();
  m.block<1, 3>(0, 0) = r.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -r.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m;
}

Mat4f OrbitCamera::projection(float aspect) const {
  const float n = std::max(distance * 0.01f, 1e-4f);
  const float f = distance * 100.0f + 1.0f;
  const float t = 1.0f / std::tan(fov_y * 0.5f);
  Mat4f m = Mat4f::Zero();
  m(0, 0) = t / std::max(aspect, 1e-6f);
  m(1, 1) = t;
  m(2, 2) = (f + n) / (n - f);
  m(2, 3) = 2.0f * f * n / (n - f);
  m(3, 2) = -1.0f;
  return m;
}

Mat4f OrbitCamera::view_projection(float aspect) const {
  return projection(aspect) * view();
}

void OrbitCamera::orbit(float dx_px, float dy_px) {
  yaw += dx_px * 0.01f;
  pitch = std::clamp(pitch + dy_px * 0.01f, -1.55f, 1.55f);
}

void OrbitCamera::pan(float dx_px, float dy_px, float viewport_h) {
  target -= view_plane_offset(dx_px, dy_px, distance, viewport_h);
}

void OrbitCamera::zoom(float wheel_steps) {
  distance = std::clamp(distance * std::pow(0.9f, wheel_steps), 1e-3f, 1e6f);
}

void OrbitCamera::fit(const Vec3f& lo, const Vec3f& hi) {
  target = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * (hi - lo).norm(), 1e-3f);
  distance = radius / std::sin(fov_y * 0.5f) * 1.05f;
}

void OrbitCamera::fit_tight(const Vec3f& lo, const Vec3f& hi, float aspect, float margin) {
  fit(lo, hi);
  const Viewport vp{0.0f, 0.0f, 2.0f * aspect, 2.0f};
  auto fits = [&](float d) {
    OrbitCamera c = *this;
    c.distance = d;
    const Mat4f m = c.view_projection(aspect);
    for (int i = 0; i < 8; ++i) {
      const Vec3f corner((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(),
                         (i & 4) ? hi.z() : lo.z());
      const ScreenPoint p = project(m, vp, corner);
      const float nx = p.x / aspect - 1.0f, ny = p.y - 1.0f;  // in [-1, 1] when inside
      if (!p.visible || std::abs(nx) > 1.0f - margin || std::abs(ny) > 1.0f - margin) return false;
    }
    return true;
  };
  // The sphere's distance always fits; bisect towards the nearest distance that still does.
  float far_d = distance, near_d = distance * 0.2f;
  if (!fits(far_d)) return;
  for (int k = 0; k < 30; ++k) {
    const float mid = 0.5f * (far_d + near_d);
    (fits(mid) ? far_d : near_d) = mid;
  }
  distance = far_d;
}

float OrbitCamera::pixel_size_at(float depth, float viewport_h) const {
  return 2.0f * depth * std::tan(fov_y * 0.5f) / std::max(viewport_h, 1.0f);
}

Vec3f OrbitCamera::view_plane_offset(float dx_px, float dy_px, float depth,
                                     float viewport_h) const {
  const float s = pixel_size_at(depth, viewport_h);
  return s * (dx_px * right() - dy_px * up());
}

ScreenPoint project(const Mat4f& view_proj, const Viewport& vp, const Vec3f& p) {
  ScreenPoint s;
  if (!p.allFinite()) return s;
  const Eigen::Vector4f c = view_proj * Eigen::Vector4f(p.x(), p.y(), p.z(), 1.0f);
  if (!(c.w() > 1e-6f)) return s;
  const float nx = c.x() / c.w(), ny = c.y() / c.w();
  s.x = vp.x + (nx * 0.5f + 0.5f) * vp.w;
  s.y = vp.y + (0.5f - ny * 0.5f) * vp.h;
  s.depth = c.w();  // clip w = eye-space distance along the view direction
  s.visible = std::isfinite(s.x) && std::isfinite(s.y);
  return s;
}

}  // namespace dampbound::ui
