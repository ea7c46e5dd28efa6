#pragma once
// Headless host: an OpenGL 3.3 core context made with EGL and no display (Mesa's surfaceless
// platform, else an EGL device such as a GPU), rendering ImGui frames into a framebuffer
// object and reading them back as an Image. Needs no X server, no window, no GLFW.
#include "ui/frame_renderer.hpp"
#include "ui/image.hpp"

#include <memory>
#include <string>

namespace dampbound::ui {

/// Which EGL platform makes the context.
enum class EglPlatform {
  Auto,         ///< surfaceless first, then each EGL device in turn
  Surfaceless,  ///< EGL_PLATFORM_SURFACELESS_MESA (llvmpipe on a machine without a GPU)
  Device        ///< EGL_PLATFORM_DEVICE_EXT (a GPU's EGL device, or Mesa's software device)
};

/// "auto", "surfaceless" or "device"; throws std::runtime_error for anything else.
EglPlatform parse_egl_platform(const std::string& name);

/// Options of the headless host.
struct EglOptions {
  EglPlatform platform = EglPlatform::Auto;
  RenderOptions render = default_render_options();
};

/// Defaults: automatic platform, light figure style. The environment variable
/// DAMPBOUND_EGL_PLATFORM (auto|surfaceless|device), when set, picks the platform.
EglOptions default_egl_options();

/// Timings of the last render_frames() call, in milliseconds of wall time. Each frame ends
/// with glFinish, so a frame's time includes the GPU (or llvmpipe) work.
struct RenderStats {
  int frames = 0;
  double first_frame_ms = 0.0;  ///< includes building the font atlas and compiling shaders
  double mean_frame_ms = 0.0;   ///< mean of the frames after the first (the first if only one)
  double readback_ms = 0.0;     ///< glReadPixels and the vertical flip
};

/// The headless host. Construction makes the EGL context (throws std::runtime_error with a
/// one-line reason when it cannot); the context is current on the constructing thread.
class EglHost {
 public:
  explicit EglHost(const EglOptions& options = default_egl_options());
  ~EglHost();
  EglHost(const EglHost&) = delete;
  EglHost& operator=(const EglHost&) = delete;

  /// Renders n_frames frames of width x height pixels, calling fn once per frame (the frame
  /// function may end the run early with info.close), and returns the last frame, top row
  /// first. Each call starts a fresh ImGui context, so the image depends only on fn and the
  /// size. The default two frames let auto-sized windows settle. Throws std::runtime_error on
  /// a bad size or a GL failure.
  Image render_frames(int width, int height, const FrameFn& fn, int n_frames = 2);

  /// "surfaceless" or "device N".
  const std::string& platform_name() const;
  /// GL_RENDERER and GL_VERSION of the context (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
  const std::string& gl_renderer() const;
  const std::string& gl_version() const;
  /// Timings of the last render_frames() call.
  const RenderStats& last_stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dampbound::ui
