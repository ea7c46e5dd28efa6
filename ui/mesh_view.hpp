#pragma once
// The mesh view widget: the model rendered in 3-D (ui/mesh_renderer.hpp) inside the current
// ImGui window, with an orbit camera (left drag orbits, right or middle drag pans, the wheel
// zooms), node picking (click a node to watch it, drag it to move it in the view plane), the
// cut tool (drag a line; the springs it crosses are removed) and a colour legend.
#include <cstdint>
#include <vector>

#include "ui/camera.hpp"
#include "ui/mesh_renderer.hpp"
#include "ui/tuner.hpp"

namespace dampbound::ui {

/// What the mesh view shows (remembered in the settings).
struct MeshViewOptions {
  bool show_springs = true;
  bool show_anchors = false;
  float point_size = 5.0f;  ///< pixels
};

/// The median on-screen length (pixels) of up to 256 of the model's springs at positions x
/// (cm): how dense the mesh looks (a very large number when none is visible).
float spring_spacing_px(const ModelSpec& model, const std::vector<Vec3>& x, const Mat4f& view_proj,
                        const Viewport& vp);

class MeshView {
 public:
  MeshViewOptions options;
  bool cut_tool = false;  ///< left drag draws a cut line instead of orbiting
  /// Per node 0..1: colour the nodes by it (shade_color) instead of their state; empty: by
  /// state. Whoever sets it bumps shade_version (the image is drawn again).
  std::vector<float> shade;
  std::uint64_t shade_version = 0;

  /// Draws the toolbar, the view filling the rest of the current window, and the legend, and
  /// applies the mouse to the camera and the tuner. Needs the GL context current.
  void draw(Tuner& tuner);

  /// Frames the scene (rest positions and the perturbed state) on the next draw.
  void request_fit() { fit_pending_ = true; }
  /// The camera (orbit, pan, zoom state).
  OrbitCamera& camera() { return camera_; }
  /// Where the view was drawn in the last frame (screen pixels).
  const Viewport& viewport() const { return viewport_; }

  /// Deletes the GL objects (context current).
  void release_gl() {
    renderer_.release();
    texture_ = 0;
  }

 private:
  enum class Drag { none, orbit, pan, node, cut };
  void handle_input(Tuner& tuner, const Viewport& vp, bool hovered);
  void draw_overlays(const Tuner& tuner, const Viewport& vp) const;
  /// The node under the mouse: a ring and a tooltip with its state and bounds.
  void node_tooltip(const Tuner& tuner, const Viewport& vp) const;
  void fit(const Tuner& tuner, float aspect);

  MeshRenderer renderer_;
  OrbitCamera camera_;
  Viewport viewport_;
  bool springs_left_out_ = false;  ///< the last image left the shown springs out (playing)
  bool fit_pending_ = true;
  const void* fitted_scene_ = nullptr;
  /// What the last rendered image showed: it is drawn again only when this changes.
  struct ImageKey {
    std::uint64_t state = 0, topology = 0;
    Mat4f view_proj = Mat4f::Zero();
    int width = 0, height = 0;
    float point_size = 0;
    bool springs = false, anchors = false;
    std::uint64_t shade = 0;
    bool operator==(const ImageKey& o) const {
      return state == o.state && topology == o.topology && shade == o.shade &&
             view_proj == o.view_proj &&
             width == o.width && height == o.height && point_size == o.point_size &&
             springs == o.springs && anchors == o.anchors;
    }
  };
  ImageKey drawn_;
  unsigned texture_ = 0;
  Drag drag_ = Drag::none;
  int drag_node_ = -1;
  float drag_distance_ = 0.0f;  ///< pixels moved since the press
  float cut_from_[2] = {0, 0}, cut_to_[2] = {0, 0};
};

}  // namespace dampbound::ui
