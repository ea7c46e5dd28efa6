#include "ui/mesh_pick.hpp"

#include <algorithm>
#include <cmath>

namespace dampbound::ui {

std::vector<ScreenPoint> project_points(const Mat4f& view_proj, const Viewport& vp,
                                        const std::vector<Vec3>& x) {
  std::vector<ScreenPoint> out;
  out.reserve(x.size());
  for (const Vec3& p : x) out.push_back(project(view_proj, vp, p.cast<float>()));
  return out;
}

int pick_node(const std::vector<ScreenPoint>& points, float mx, float my, float radius_px) {
  int best = -1;
  float best_d2 = radius_px * radius_px;
  float best_depth = 0.0f;
  for (size_t i = 0; i < points.size(); ++i) {
    const ScreenPoint& p = points[i];
    if (!p.visible) continue;
    const float dx = p.x - mx, dy = p.y - my;
    const float d2 = dx * dx + dy * dy;
    if (d2 > radius_px * radius_px) continue;
    const float d = std::sqrt(d2), bd = std::sqrt(best_d2);
    const bool nearer = best < 0 || d < bd - 0.5f;
    const bool tie_in_front = best >= 0 && std::abs(d - bd) <= 0.5f && p.depth < best_depth;
    if (nearer || tie_in_front) {
      best = static_cast<int>(i);
      best_d2 = d2;
      best_depth = p.depth;
    }
  }
  return best;
}

namespace {
/// Twice the signed area of (a, b, c): > 0 when c is left of a->b.
double orient(const Vec2f& a, const Vec2f& b, const Vec2f& c) {
  return (static_cast<double>(b.x()) - a.x()) * (static_cast<double>(c.y()) - a.y()) -
         (static_cast<double>(b.y()) - a.y()) * (static_cast<double>(c.x()) - a.x());
}

/// c collinear with a-b lies within their bounding box.
bool on_segment(const Vec2f& a, const Vec2f& b, const Vec2f& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

int sign(double v) {
  return (v > 0) - (v < 0);
}
}  // namespace

bool segments_intersect(const Vec2f& a0, const Vec2f& a1, const Vec2f& b0, const Vec2f& b1) {
  const int o1 = sign(orient(a0, a1, b0)), o2 = sign(orient(a0, a1, b1));
  const int o3 = sign(orient(b0, b1, a0)), o4 = sign(orient(b0, b1, a1));
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && on_segment(a0, a1, b0)) return true;
  if (o2 == 0 && on_segment(a0, a1, b1)) return true;
  if (o3 == 0 && on_segment(b0, b1, a0)) return true;
  if (o4 == 0 && on_segment(b0, b1, a1)) return true;
  return false;
}

std::vector<int> springs_crossing_screen(const ModelSpec& model, const std::vector<ScreenPoint>& points,
                                         const Vec2f& p0, const Vec2f& p1) {
  std::vector<int> out;
  for (int s = 0; s < model.spring_count(); ++s) {
    const Spring& sp = model.springs[static_cast<size_t>(s)];
    if (sp.i < 0 || sp.j < 0 || static_cast<size_t>(sp.i) >= points.size() ||
        static_cast<size_t>(sp.j) >= points.size())
      continue;
    const ScreenPoint& a = points[static_cast<size_t>(sp.i)];
    const ScreenPoint& b = points[static_cast<size_t>(sp.j)];
    if (!a.visible || !b.visible) continue;
    if (segments_intersect(Vec2f(a.x, a.y), Vec2f(b.x, b.y), p0, p1)) out.push_back(s);
  }
  return out;
}

bool bounding_box(const std::vector<Vec3>& x, Vec3f& lo, Vec3f& hi) {
  bool any = false;
  for (const Vec3& p : x) {
    if (!p.allFinite()) continue;
    const Vec3f q = p.cast<float>();
    if (!any) {
      lo = hi = q;
      any = true;
    } else {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  }
  return any;
}

}  // namespace dampbound::ui
