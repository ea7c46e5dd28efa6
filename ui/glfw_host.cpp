#include "ui/glfw_host.hpp"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>

#include <GL/gl.h>
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <vector>
#include <mutex>
#include <stdexcept>

namespace dampbound::ui {

namespace {

std::mutex g_glfw_mutex;
int g_glfw_users = 0;
std::string g_glfw_error;  ///< the last message GLFW reported

void on_glfw_error(int /*code*/, const char* description) {
  g_glfw_error = description != nullptr ? description : "unknown GLFW error";
}

/// glfwInit once for all hosts; glfwTerminate when the last one goes.
void acquire_glfw() {
  std::lock_guard<std::mutex> lock(g_glfw_mutex);
  if (g_glfw_users == 0) {
    g_glfw_error.clear();
    glfwSetErrorCallback(on_glfw_error);
    if (glfwInit() != GLFW_TRUE) {
      throw std::runtime_error("GLFW: cannot open a window: " +
                               (g_glfw_error.empty() ? std::string("glfwInit failed") : g_glfw_error));
    }
  }
  ++g_glfw_users;
}

void release_glfw() {
  std::lock_guard<std::mutex> lock(g_glfw_mutex);
  if (--g_glfw_users == 0) glfwTerminate();
}

/// Key taps shorter than a frame: ImGui 1.86 reads the keys' state once per frame, so a key
/// pressed and released between two frames (xdotool's `key`, a quick tap on a slow frame)
/// never reads as down and the tap is lost. A release that arrives in the same frame as its
/// press is held back to the next frame: the key then reads as pressed for exactly one frame.
struct KeyTaps {
  GLFWwindow* window = nullptr;
  GLFWkeyfun imgui = nullptr;  ///< ImGui's callback, which this one chains to
  std::vector<int> pressed;    ///< keys pressed since the last frame began
  struct Held {
    int key, scancode, mods;
  };
  std::vector<Held> held;  ///< releases held back to the next frame
};
KeyTaps g_taps;  // the main thread's window (one at a time)

void on_key(GLFWwindow* window, int key, int scancode, int action, int mods) {
  if (action == GLFW_RELEASE &&
      std::find(g_taps.pressed.begin(), g_taps.pressed.end(), key) != g_taps.pressed.end()) {
    g_taps.held.push_back({key, scancode, mods});
    return;
  }
  if (action == GLFW_PRESS) g_taps.pressed.push_back(key);
  if (g_taps.imgui != nullptr) g_taps.imgui(window, key, scancode, action, mods);
}

/// Before a frame's events: the releases held back in the last frame, then a new frame.
/// The window's on_close_request (one window at a time, as g_taps).
std::function<void()> g_on_close;
void on_close(GLFWwindow* /*window*/) {
  if (g_on_close) g_on_close();
}

void release_held_keys() {
  for (const KeyTaps::Held& h : g_taps.held)
    if (g_taps.imgui != nullptr) g_taps.imgui(g_taps.window, h.key, h.scancode, GLFW_RELEASE, h.mods);
  g_taps.held.clear();
  g_taps.pressed.clear();
}

}  // namespace

WindowOptions default_window_options() { return WindowOptions{}; }

struct GlfwHost::Impl {
  WindowOptions options;
  GLFWwindow* window = nullptr;
  std::unique_ptr<FrameRenderer> renderer;
  bool platform_backend = false;
  std::string renderer_name;
};

GlfwHost::GlfwHost(const WindowOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  acquire_glfw();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
  impl_->window = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (impl_->window == nullptr) {
    const std::string why = g_glfw_error.empty() ? "glfwCreateWindow failed" : g_glfw_error;
    release_glfw();
    throw std::runtime_error("GLFW: cannot open an OpenGL 3.3 window: " + why);
  }
  glfwMakeContextCurrent(impl_->window);
  glfwSwapInterval(options.vsync ? 1 : 0);
  try {
    impl_->renderer = std::make_unique<FrameRenderer>(options.render);
  } catch (...) {
    glfwDestroyWindow(impl_->window);
    release_glfw();
    throw;
  }
  impl_->platform_backend = ImGui_ImplGlfw_InitForOpenGL(impl_->window, true);
  if (impl_->platform_backend) {
    g_taps = KeyTaps{};
    g_taps.window = impl_->window;
    g_taps.imgui = glfwSetKeyCallback(impl_->window, on_key);
  }
  impl_->renderer_name = gl_string(GL_RENDERER);
  g_on_close = options.on_close_request;
  glfwSetWindowCloseCallback(impl_->window, on_close);
}

GlfwHost::~GlfwHost() {
  glfwSetWindowCloseCallback(impl_->window, nullptr);
  g_on_close = nullptr;
  glfwMakeContextCurrent(impl_->window);
  ImGui::SetCurrentContext(impl_->renderer->context());
  if (impl_->platform_backend) {
    glfwSetKeyCallback(impl_->window, g_taps.imgui);  // ImGui's own, for its shutdown
    g_taps = KeyTaps{};
    ImGui_ImplGlfw_Shutdown();
  }
  impl_->renderer.reset();
  glfwDestroyWindow(impl_->window);
  release_glfw();
}

WindowRun GlfwHost::run(const FrameFn& fn) {
  using Clock = std::chrono::steady_clock;
  WindowRun result;
  GLFWwindow* win = impl_->window;
  const WindowOptions& opt = impl_->options;
  const double t0 = glfwGetTime();
  const auto wall0 = Clock::now();
  FrameInfo info;
  while (glfwWindowShouldClose(win) == GLFW_FALSE) {
    const auto frame_start = Clock::now();
    if (g_taps.window == win) release_held_keys();
    glfwPollEvents();
    if (glfwWindowShouldClose(win) == GLFW_TRUE) break;  // closed now: no frame after it
    // Another host (e.g. an EGL export) may have taken the thread's context meanwhile.
    glfwMakeContextCurrent(win);
    int fb_w = 0, fb_h = 0, w = 0, h = 0;
    glfwGetFramebufferSize(win, &fb_w, &fb_h);
    glfwGetWindowSize(win, &w, &h);
    if (fb_w <= 0 || fb_h <= 0) {  // minimised
      glfwWaitEventsTimeout(0.05);
      continue;
    }
    ImGui::SetCurrentContext(impl_->renderer->context());
    if (impl_->platform_backend) ImGui_ImplGlfw_NewFrame();
    if (opt.input) opt.input();
    info.index = result.frames;
    info.width = w;
    info.height = h;
    info.time_s = glfwGetTime() - t0;
    const float dt = impl_->platform_backend ? 0.0f : 1.0f / 60.0f;
    // The first frame is built twice: the window then opens on ImGui's settled layout.
    if (result.frames == 0) impl_->renderer->layout_pass(info, fn, dt, fb_w, fb_h);
    impl_->renderer->frame(info, fn, dt, fb_w, fb_h);
    if (result.frames == opt.screenshot_frame) {
      glReadBuffer(GL_BACK);
      result.screenshot = read_pixels(fb_w, fb_h);
    }
    glfwSwapBuffers(win);
    result.frame_ms.push_back(
        std::chrono::duration<double, std::milli>(Clock::now() - frame_start).count());
    ++result.frames;
    if (info.close) glfwSetWindowShouldClose(win, GLFW_TRUE);
    if (opt.max_frames > 0 && result.frames >= opt.max_frames) break;
  }
  if (result.frames > 0) {
    result.mean_frame_ms =
        std::chrono::duration<double, std::milli>(Clock::now() - wall0).count() / result.frames;
  }
  return result;
}

const std::string& GlfwHost::gl_renderer() const { return impl_->renderer_name; }

}  // namespace dampbound::ui
