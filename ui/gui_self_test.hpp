#pragma once
// `dampbound gui --self-test`: the tuner operated through ImGui's input state, as a person
// would, with no one at the keyboard. On each scene it visits every widget the frames draw
// (ui/gui_items.hpp's log): clicks each tab, button, checkbox and combo (and an entry of its
// list), drags each slider, types into each text and number field, turns on the cut tool and
// drags a cut across the mesh, drags the mesh and the plots. Then, on the monkey's scenes, a
// seeded random sequence of clicks, drags, wheel turns, keys and characters.
#include <imgui.h>

#include <cstdint>
#include <deque>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "ui/frame_renderer.hpp"
#include "ui/gui_items.hpp"

namespace dampbound::ui {

class GuiApp;

struct SelfTestOptions {
  std::vector<std::string> scenes;         ///< scene files visited widget by widget
  std::vector<std::string> monkey_scenes;  ///< scene files the monkey plays on
  int monkey_events = 1000;                ///< per monkey scene
  std::uint64_t seed = 1;
};

/// What the self-test did.
struct SelfTestReport {
  std::set<std::string> visited;  ///< "kind 'label' in window", over all scenes
  int scenes_visited = 0;
  int monkey_events = 0;  ///< over all monkey scenes
  int frames = 0;
};

/// One frame of synthetic input.
struct SyntheticInput {
  ImVec2 pos{-1, -1};
  bool left = false, right = false;
  float wheel = 0.0f;
  int key = -1;        ///< an ImGuiKey_ pressed during this frame
  unsigned chars = 0;  ///< a character typed (0: none)
};

class SelfTest {
 public:
  SelfTest(GuiApp& app, SelfTestOptions options);
  /// Writes this frame's synthetic input into `io` (after the platform backend's, before
  /// NewFrame).
  void input(ImGuiIO& io);
  /// Plans what follows from the items the frame drew; true when the test is over.
  bool after_frame(const FrameInfo& info);
  const SelfTestReport& report() const { return report_; }
  /// What is being done now (a hang's message).
  const std::string& doing() const { return doing_; }

 private:
  void next_scene();
  bool plan_visit();
  void plan_monkey_event();
  void operate(const ItemRecord& item);
  void click(ImVec2 p, bool right = false);
  void drag(ImVec2 a, ImVec2 b, bool right = false);
  void type(const std::string& text, bool enter);
  ImVec2 random_point();

  GuiApp& app_;
  SelfTestOptions options_;
  SelfTestReport report_;
  std::deque<SyntheticInput> queue_;
  ImVec2 last_pos_{-1, -1};
  int pending_key_ = -1;        ///< a key held down in the last frame, released now
  std::set<std::string> seen_;  ///< items operated on the current scene
  size_t scene_ = 0;            ///< index into visits then monkey scenes
  bool started_ = false;
  bool monkey_ = false;
  int monkey_left_ = 0;
  int idle_plans_ = 0;
  int knobs_again_ = 0;  ///< times "Ceiling and pair" was pressed again on this scene
  bool knobs_applied_ = false;
  int scrolls_ = 0;  ///< wheel turns over the runs' panel on this scene  ///< an apply button of the ceiling or the pair was operated
  std::mt19937_64 rng_;
  void set_doing(std::string what);
  static constexpr double kSlowStepSeconds = 5;
  std::string doing_;
  double doing_since_ = 0;
  float width_ = 0, height_ = 0;
};

}  // namespace dampbound::ui
