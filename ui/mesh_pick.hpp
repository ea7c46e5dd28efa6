#pragma once
// Screen-space geometry of the mesh view: projecting nodes, picking the node under the mouse,
// and the cut tool's segment test. Pure maths, no GL (tests/ui/mesh_pick_test.cpp).
#include <vector>

#include "dampbound/physics/model.hpp"
#include "ui/camera.hpp"

namespace dampbound::ui {

/// Every position projected into the viewport (ScreenPoint::visible false behind the camera
/// or for a non-finite position).
std::vector<ScreenPoint> project_points(const Mat4f& view_proj, const Viewport& vp,
                                        const std::vector<Vec3>& x);

/// The node nearest to the mouse (mx, my) within `radius_px` pixels; among nodes equally
/// near (within half a pixel) the one nearest the camera. -1 when none.
int pick_node(const std::vector<ScreenPoint>& points, float mx, float my, float radius_px);

/// True when the closed 2-D segments a0-a1 and b0-b1 intersect (touching counts; collinear
/// overlapping segments count). Degenerate segments (points) are handled.
bool segments_intersect(const Vec2f& a0, const Vec2f& a1, const Vec2f& b0, const Vec2f& b1);

/// Indices of the springs whose projected segment crosses the screen segment p0-p1 (the cut
/// tool's drag line). A spring with an endpoint behind the camera is never cut.
std::vector<int> springs_crossing_screen(const ModelSpec& model, const std::vector<ScreenPoint>& points,
                                         const Vec2f& p0, const Vec2f& p1);

/// Axis-aligned bounding box of the finite positions; false when there are none.
bool bounding_box(const std::vector<Vec3>& x, Vec3f& lo, Vec3f& hi);

}  // namespace dampbound::ui
