#pragma once
// Shared helpers of the ui tests (one definition each: the tests build in unity batches).
#include <cstdlib>
#include <filesystem>
#include <string>

#include "dampbound/run/scene.hpp"
#include "ui/egl_host.hpp"
#include "ui/frame_renderer.hpp"

namespace dampbound::ui::ui_test {

/// A small version of the paper's plane: a side x side grid, anchors, the centre node lifted;
/// named "small-plane", with the scene's iteration limit unless `max_iterations` > 0.
inline SceneSpec small_plane(int side = 10, int max_iterations = 0) {
  SceneSpec s = paper_plane_scene(side);
  s.name = "small-plane";
  if (max_iterations > 0) s.rules.max_iterations = max_iterations;
  return s;
}

/// Where a test writes the PNG it renders: $DAMPBOUND_UI_PNG_DIR, else ./ui_test_output.
inline std::string out_path(const std::string& name) {
  const char* env = std::getenv("DAMPBOUND_UI_PNG_DIR");
  const std::filesystem::path dir = env != nullptr && *env != '\0' ? env : "ui_test_output";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

/// The EGL host with the window's render options.
inline EglOptions headless() {
  EglOptions eo;
  eo.render = gui_render_options();
  return eo;
}

}  // namespace dampbound::ui::ui_test
