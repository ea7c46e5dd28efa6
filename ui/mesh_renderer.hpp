#pragma once
// Draws the mass-spring model with OpenGL 3.3 core shaders into an offscreen texture, which
// the mesh view shows with ImGui::Image: the same code runs in the GLFW window and under the
// headless EGL host. Springs are lines, nodes round points coloured by their state in the
// last step (ui/mesh_style.hpp). Per frame only positions and colours are uploaded; the
// spring index buffer is rebuilt when the topology changes (a cut, a reset).
#include <cstdint>
#include <vector>

#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/model.hpp"
#include "ui/camera.hpp"

namespace dampbound::ui {

/// What one render draws.
struct MeshDrawData {
  const Model* model = nullptr;
  const std::vector<Vec3>* x = nullptr;             ///< current positions (cm)
  const std::vector<NodeStatus>* status = nullptr;  ///< per node; empty: all "within"
  /// gamma_safe_i per node (SPEC 9; null or empty: not shown): nodes with gamma_lo_i above it
  /// are drawn with node_color(status, true).
  const std::vector<double>* safe_bound = nullptr;
  /// Per node 0..1 (null, or not one per node: not shown): nodes coloured by shade_color
  /// instead of their state (the Suggest tab's added mass, SPEC 11).
  const std::vector<float>* shade = nullptr;
  std::uint64_t topology = 0;                       ///< changes whenever model->springs changes
  Mat4f view_proj = Mat4f::Identity();
  float point_size = 6.0f;  ///< node diameter (pixels)
  /// Opacity of the spring lines (0..1): below 1 on dense meshes, where one-pixel lines a few
  /// pixels apart beat against the pixel grid (moire).
  float spring_alpha = 1.0f;
  float point_alpha = 1.0f;  ///< opacity of the nodes (0..1), lowered on dense meshes too
  bool springs = true;
  bool anchors = false;  ///< lines from each anchored node to its rest position
  int samples = 1;       ///< multisampling (1: none; 4 smooths lines, costs fill rate)
  float background[4] = {0.12f, 0.13f, 0.15f, 1.0f};
};

/// Owns the shaders, buffers and framebuffer. Create and use it with a GL 3.3 context current;
/// GL objects are made on the first render(). Call release() with the context current before
/// the context goes; the destructor does not touch GL.
class MeshRenderer {
 public:
  MeshRenderer() = default;
  MeshRenderer(const MeshRenderer&) = delete;
  MeshRenderer& operator=(const MeshRenderer&) = delete;

  /// Renders into a width x height colour texture (multisampled and resolved when
  /// data.samples > 1 and available) and returns the texture's GL name (0 when GL failed). The draw
  /// framebuffer, viewport and program bound before are bound again after.
  unsigned render(const MeshDrawData& data, int width, int height);

  /// Deletes the GL objects (the context that made them must be current).
  void release();

  /// Samples per pixel of the multisampled target (1: none).
  int samples() const { return samples_; }

 private:
  bool init();
  void resize(int width, int height, int samples);
  void upload(const MeshDrawData& data);

  bool ready_ = false, failed_ = false;
  unsigned program_ = 0, vao_ = 0, anchor_vao_ = 0;
  unsigned vbo_pos_ = 0, vbo_col_ = 0, ebo_ = 0, vbo_anchor_ = 0, vbo_anchor_col_ = 0;
  unsigned fbo_ms_ = 0, rb_color_ = 0, rb_depth_ = 0;  ///< multisampled (or plain) target
  unsigned fbo_tex_ = 0, tex_ = 0;                     ///< resolved texture shown by ImGui
  int loc_mvp_ = -1, loc_point_size_ = -1, loc_tint_ = -1, loc_use_tint_ = -1, loc_round_ = -1;
  int loc_point_alpha_ = -1;
  int width_ = 0, height_ = 0, samples_ = 1, max_samples_ = 1;
  std::uint64_t topology_ = 0;
  const Model* model_ = nullptr;
  int index_count_ = 0, node_count_ = 0, anchor_vertices_ = 0;
  std::vector<float> pos_, anchor_pos_;
  std::vector<std::uint8_t> col_, anchor_col_;
};

}  // namespace dampbound::ui
