#include "ui/frame_renderer.hpp"

#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>

#include <GL/gl.h>
#include <GL/glext.h>

#include <cstring>
#include <stdexcept>

namespace dampbound::ui {

RenderOptions default_render_options() { return RenderOptions{}; }

RenderOptions gui_render_options() {
  RenderOptions o;
  o.theme = Theme::Dark;
  o.clear_color = {0.10f, 0.10f, 0.11f, 1.0f};
  return o;
}

FrameRenderer::FrameRenderer(const RenderOptions& options) : options_(options) {
  IMGUI_CHECKVERSION();
  previous_ = ImGui::GetCurrentContext();
  ctx_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(ctx_);
  ImGuiIO& io = ImGui::GetIO();
  ini_path_ = options.ini_path;
  io.IniFilename = ini_path_.empty() ? nullptr : ini_path_.c_str();
  io.LogFilename = nullptr;
  fonts_ = load_fonts(options.fonts);
  apply_theme(options.theme, options.fonts.size_px);
  // GLSL 3.30 matches the 3.3 core context both hosts ask for.
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
    ImGui::DestroyContext(ctx_);
    ImGui::SetCurrentContext(previous_);
    ctx_ = nullptr;
    throw std::runtime_error("ImGui OpenGL3 backend failed to start (no OpenGL 3.3 entry points)");
  }
}

FrameRenderer::~FrameRenderer() {
  if (ctx_ == nullptr) return;
  ImGui::SetCurrentContext(ctx_);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(ctx_);
  ImGui::SetCurrentContext(previous_);
}

namespace {

void begin_frame(const FrameInfo& info, float dt, int fb_w, int fb_h) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(info.width), static_cast<float>(info.height));
  if (info.width > 0 && info.height > 0) {
    io.DisplayFramebufferScale = ImVec2(static_cast<float>(fb_w) / static_cast<float>(info.width),
                                        static_cast<float>(fb_h) / static_cast<float>(info.height));
  }
  if (dt > 0.0f) io.DeltaTime = dt;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
}

}  // namespace

void FrameRenderer::layout_pass(FrameInfo& info, const FrameFn& fn, float dt, int fb_w, int fb_h) {
  ImGui::SetCurrentContext(ctx_);
  begin_frame(info, dt, fb_w, fb_h);
  info.layout_pass = true;
  if (fn) fn(info);
  info.layout_pass = false;
  ImGui::EndFrame();
}

void FrameRenderer::frame(FrameInfo& info, const FrameFn& fn, float dt, int fb_w, int fb_h) {
  ImGui::SetCurrentContext(ctx_);
  begin_frame(info, dt, fb_w, fb_h);
  if (fn) fn(info);
  ImGui::Render();
  glViewport(0, 0, fb_w, fb_h);
  const auto& c = options_.clear_color;
  glClearColor(c[0], c[1], c[2], c[3]);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

Image read_pixels(int width, int height) {
  Image img;
  img.width = width;
  img.height = height;
  const size_t row = static_cast<size_t>(width) * 4;
  std::vector<uint8_t> raw(row * static_cast<size_t>(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
  const GLenum err = glGetError();
  if (err != GL_NO_ERROR) {
    throw std::runtime_error("glReadPixels failed with GL error " + std::to_string(err));
  }
  // GL rows start at the bottom; images start at the top.
  img.rgba.resize(raw.size());
  for (int y = 0; y < height; ++y) {
    std::memcpy(img.rgba.data() + static_cast<size_t>(y) * row,
                raw.data() + static_cast<size_t>(height - 1 - y) * row, row);
  }
  for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
  return img;
}

std::string gl_string(unsigned name) {
  const GLubyte* s = glGetString(static_cast<GLenum>(name));
  return s == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(s));
}

}  // namespace dampbound::ui
