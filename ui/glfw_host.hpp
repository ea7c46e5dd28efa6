#pragma once
// Windowed host: a GLFW window with an OpenGL 3.3 core context, ImGui's GLFW platform
// backend for input, and the shared FrameRenderer (ui/frame_renderer.hpp) for drawing.
// The frame functions are the same ones the headless EGL host runs.
#include "ui/frame_renderer.hpp"
#include "ui/image.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dampbound::ui {

/// Options of the window host.
struct WindowOptions {
  int width = 1280;  ///< window size in screen coordinates
  int height = 800;
  std::string title = "dampbound";
  bool vsync = true;
  bool visible = true;
  int max_frames = 0;         ///< end after this many frames; 0: when the window closes
  int screenshot_frame = -1;  ///< copy the back buffer after drawing this frame (-1: never)
  RenderOptions render = gui_render_options();
  /// Called each frame after the window's input reached ImGui's io and before the frame is
  /// built: a scripted input source (gui --self-test) writes its own there.
  std::function<void()> input;
  /// Called from the event poll the moment a close is requested (the window manager's close
  /// button): the close guard starts its grace period there, not after the frame. The frame
  /// loop then ends before building another frame.
  std::function<void()> on_close_request;
};

/// Defaults: 1280x800, vsync, dark theme, runs until closed.
WindowOptions default_window_options();

/// What a run() did.
struct WindowRun {
  int frames = 0;
  double mean_frame_ms = 0.0;       ///< wall time per frame (includes vsync waits)
  std::vector<double> frame_ms;     ///< each frame's wall time, event poll to buffer swap (ms)
  std::optional<Image> screenshot;  ///< set when screenshot_frame was reached
};

/// The window host. Construction opens the window and throws std::runtime_error with a
/// one-line reason when it cannot (no display, no OpenGL 3.3).
class GlfwHost {
 public:
  explicit GlfwHost(const WindowOptions& options = default_window_options());
  ~GlfwHost();
  GlfwHost(const GlfwHost&) = delete;
  GlfwHost& operator=(const GlfwHost&) = delete;

  /// Calls fn once per frame until the window is closed, fn sets info.close, or max_frames
  /// frames were drawn. The first frame calls it twice: a layout pass (info.layout_pass, never
  /// drawn), then the frame itself.
  WindowRun run(const FrameFn& fn);

  /// GL_RENDERER of the window's context.
  const std::string& gl_renderer() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dampbound::ui
