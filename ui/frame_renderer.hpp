#pragma once
// What the two hosts share: the ImGui context, fonts, theme, the OpenGL3 backend and the
// frame order. A host only makes a GL context current and says where the pixels go (a window's
// back buffer, or a framebuffer object that is read back). A frame function issues ImGui
// calls; the renderer wraps it in NewFrame ... Render and draws the result.
#include "ui/fonts.hpp"
#include "ui/image.hpp"

#include <array>
#include <functional>
#include <string>

struct ImGuiContext;

namespace dampbound::ui {

/// What a frame function is told about the frame it builds.
struct FrameInfo {
  int index = 0;        ///< 0 for the first frame of a run
  int width = 0;        ///< display size in pixels (io.DisplaySize)
  int height = 0;
  double time_s = 0.0;  ///< seconds since the first frame (headless: index / 60)
  bool close = false;   ///< the frame function sets it to end the run after this frame
  /// True on a pass that is built but never drawn (FrameRenderer::layout_pass): ImGui measures
  /// tab bars, table columns and auto-fitted windows from one frame's contents and places
  /// them the frame after. On it a frame function builds its windows and advances nothing.
  bool layout_pass = false;
};

/// Builds one ImGui frame: called between ImGui::NewFrame() and ImGui::Render(), with the
/// host's ImGui context current. It must not call NewFrame/Render itself.
using FrameFn = std::function<void(FrameInfo&)>;

/// Fonts, theme, background colour and settings file of a host.
struct RenderOptions {
  FontOptions fonts = default_font_options();
  Theme theme = Theme::Light;
  std::array<float, 4> clear_color{1.0f, 1.0f, 1.0f, 1.0f};  ///< RGBA in 0..1
  std::string ini_path;  ///< ImGui window-settings file; empty: none is read or written
};

/// Figures: light theme, white background, 16 px DejaVu Sans, no settings file.
RenderOptions default_render_options();
/// The interactive GUI: dark theme, dark background.
RenderOptions gui_render_options();

/// Owns an ImGui context and the OpenGL3 backend for the GL context current at construction
/// (which must stay current while it is used); the ImGui context that was current before is
/// current again after destruction. Throws std::runtime_error when the backend
/// cannot start (no GL 3.x entry points).
class FrameRenderer {
 public:
  explicit FrameRenderer(const RenderOptions& options);
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  /// The ImGui context (current after construction). A platform backend (GLFW) attaches to it.
  ImGuiContext* context() const { return ctx_; }
  const LoadedFonts& fonts() const { return fonts_; }

  /// One frame: sets io.DisplaySize to info.width x info.height (framebuffer fb_w x fb_h),
  /// io.DeltaTime to dt when dt > 0, runs NewFrame, fn(info), Render, then clears the bound
  /// draw framebuffer and draws the ImGui draw data into it.
  void frame(FrameInfo& info, const FrameFn& fn, float dt, int fb_w, int fb_h);

  /// A frame that is built and thrown away: NewFrame, fn(info) with info.layout_pass set,
  /// EndFrame; nothing is drawn. A window's first frame() after it shows what ImGui laid out
  /// from it instead of ImGui's first guess (no tab bars, text wrapped one letter per line).
  void layout_pass(FrameInfo& info, const FrameFn& fn, float dt, int fb_w, int fb_h);

 private:
  ImGuiContext* ctx_ = nullptr;
  ImGuiContext* previous_ = nullptr;  ///< made current again by the destructor
  LoadedFonts fonts_;
  RenderOptions options_;
  std::string ini_path_;  ///< keeps io.IniFilename's storage alive
};

/// Reads the bound read framebuffer's (0, 0, width, height) as RGBA, flipped so row 0 is the
/// top, alpha forced to 255 (a screenshot is opaque). Throws std::runtime_error on GL error.
Image read_pixels(int width, int height);

/// glGetString(name) of the current context, or "" when null.
std::string gl_string(unsigned name);

}  // namespace dampbound::ui
