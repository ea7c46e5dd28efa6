#include "ui/gui_export.hpp"

#include <GL/gl.h>
#include <GL/glext.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "ui/frame_renderer.hpp"
#include "ui/plot.hpp"
#include "ui/tuner_export.hpp"

namespace dampbound::ui {

Image render_plots_offscreen(const std::vector<PlotSpec>& plots, int columns, int width,
                             int height) {
  if (ImGui::GetCurrentContext() == nullptr) throw std::runtime_error("export: no ImGui context");
  // One draw list with the plots, drawn as a figure would be.
  ImDrawList dl(ImGui::GetDrawListSharedData());
  dl._ResetForNewFrame();
  dl.PushTextureID(ImGui::GetIO().Fonts->TexID);
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  dl.PushClipRect(ImVec2(0, 0), ImVec2(w, h));
  const PlotStyle style = plot_style_light();
  dl.AddRectFilled(ImVec2(0, 0), ImVec2(w, h), IM_COL32(255, 255, 255, 255));
  const int n = static_cast<int>(plots.size());
  const int cols = std::clamp(columns, 1, std::max(n, 1));
  const int rows = std::max((n + cols - 1) / cols, 1);
  const float cw = std::floor(w / static_cast<float>(cols)),
              ch = std::floor(h / static_cast<float>(rows));
  for (int i = 0; i < n; ++i) {
    const ImVec2 tl(cw * static_cast<float>(i % cols), ch * static_cast<float>(i / cols));
    draw_plot(&dl, tl, ImVec2(cw, ch), plots[static_cast<size_t>(i)], style);
  }
  dl.PopClipRect();
  dl.PopTextureID();
  ImDrawList* lists[] = {&dl};
  ImDrawData data;
  data.Valid = true;
  data.CmdLists = lists;
  data.CmdListsCount = 1;
  data.TotalVtxCount = dl.VtxBuffer.Size;
  data.TotalIdxCount = dl.IdxBuffer.Size;
  data.DisplayPos = ImVec2(0, 0);
  data.DisplaySize = ImVec2(w, h);
  data.FramebufferScale = ImVec2(1, 1);

  GLint prev_draw = 0, prev_read = 0, viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &prev_draw);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev_read);
  glGetIntegerv(GL_VIEWPORT, viewport);
  GLuint fbo = 0, rb = 0;
  glGenFramebuffers(1, &fbo);
  glGenRenderbuffers(1, &rb);
  glBindRenderbuffer(GL_RENDERBUFFER, rb);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  Image img;
  std::string error;
  if (complete) {
    glViewport(0, 0, width, height);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(&data);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    try {
      img = read_pixels(width, height);
    } catch (const std::exception& e) {
      error = e.what();
    }
  } else {
    error = "export: the offscreen framebuffer is incomplete";
  }
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(prev_draw));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(prev_read));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  glDeleteFramebuffers(1, &fbo);
  glDeleteRenderbuffers(1, &rb);
  if (!error.empty()) throw std::runtime_error(error);
  return img;
}

std::vector<PlotSpec> export_plot_specs(Tuner& tuner, TunerPlotOptions options, bool current) {
  options.full_traces = true;
  options.show_current = current;
  std::vector<PlotSpec> plots = {tuner_displacement_plot(tuner, options)};
  if (current) plots.push_back(tuner_envelope_plot(tuner, options));
  return plots;
}

std::string export_runs(Tuner& tuner, const std::vector<PlotSpec>& plots, const std::string& dir,
                        const std::string& prefix, bool current) {
  const ExportPaths paths = export_paths(dir, prefix);
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  const Image img = render_plots_offscreen(
      plots, 1, 1400, 500 * static_cast<int>(std::max<size_t>(plots.size(), 1)));
  write_png_atomic(img, paths.plots_png);
  export_csv(tuner, paths, current);
  return "wrote " + paths.plots_png + ", " + paths.traces_csv + ", " + paths.runs_csv + ", " +
         paths.step_vtu + (current ? "" : " (the unfinished current run left out)");
}

}  // namespace dampbound::ui
