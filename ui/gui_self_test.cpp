#include "ui/gui_self_test.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <utility>

#include "ui/gui_app.hpp"

namespace dampbound::ui {

namespace {

std::string stem(const std::string& path) {
  return std::filesystem::path(path).stem().string();
}

ImVec2 centre(const ItemRecord& r) {
  return ImVec2(0.5f * (r.min.x + r.max.x), 0.5f * (r.min.y + r.max.y));
}

/// The keys the monkey presses: none of them leaves the window or types a path separator.
constexpr ImGuiKey_ kMonkeyKeys[] = {ImGuiKey_Space,     ImGuiKey_Enter,      ImGuiKey_Escape,
                                     ImGuiKey_Tab,       ImGuiKey_Backspace,  ImGuiKey_Delete,
                                     ImGuiKey_LeftArrow, ImGuiKey_RightArrow, ImGuiKey_UpArrow,
                                     ImGuiKey_DownArrow, ImGuiKey_Home,       ImGuiKey_End};
constexpr char kMonkeyChars[] = "abcxyz0123456789.-e +";

}  // namespace

SelfTest::SelfTest(GuiApp& app, SelfTestOptions options)
    : app_(app), options_(std::move(options)), rng_(options_.seed) {
  item_log().on = true;
}

void SelfTest::input(ImGuiIO& io) {
  SyntheticInput s;
  s.pos = last_pos_;
  if (!queue_.empty()) {
    s = queue_.front();
    queue_.pop_front();
    if (s.pos.x < 0) s.pos = last_pos_;
  }
  last_pos_ = s.pos;
  io.MousePos = s.pos.x < 0 ? ImVec2(-FLT_MAX, -FLT_MAX) : s.pos;
  io.MouseDown[0] = s.left;
  io.MouseDown[1] = s.right;
  io.MouseWheel += s.wheel;
  if (pending_key_ >= 0 && io.KeyMap[pending_key_] >= 0)
    io.KeysDown[io.KeyMap[pending_key_]] = false;
  pending_key_ = -1;
  if (s.key >= 0 && io.KeyMap[s.key] >= 0) {
    io.KeysDown[io.KeyMap[s.key]] = true;
    pending_key_ = s.key;
  }
  if (s.chars != 0) io.AddInputCharacter(s.chars);
}

bool SelfTest::after_frame(const FrameInfo& info) {
  item_log().end_frame();
  if (info.layout_pass) return false;
  ++report_.frames;
  width_ = static_cast<float>(info.width);
  height_ = static_cast<float>(info.height);
  if (!queue_.empty()) return false;
  const size_t scenes = options_.scenes.size() + options_.monkey_scenes.size();
  if (!started_) {
    started_ = true;
    if (scenes == 0) return true;
    next_scene();
    return false;
  }
  if (monkey_ ? monkey_left_ > 0 : plan_visit()) {
    if (monkey_) plan_monkey_event();
    return false;
  }
  if (scene_ >= scenes) {
    set_doing("done");
    return true;
  }
  next_scene();
  return false;
}

void SelfTest::set_doing(std::string what) {
  // A step that took long is named in the log, so a slow CI run says where its time went.
  using clock = std::chrono::steady_clock;
  const double now = std::chrono::duration<double>(clock::now().time_since_epoch()).count();
  if (!doing_.empty() && now - doing_since_ >= kSlowStepSeconds)
    std::fprintf(stderr, "self-test: %s took %.0f s\n", doing_.c_str(), now - doing_since_);
  if (what.rfind("operating ", 0) != 0) std::fprintf(stderr, "self-test: %s\n", what.c_str());
  doing_ = std::move(what);
  doing_since_ = now;
}

void SelfTest::next_scene() {
  const size_t visits = options_.scenes.size();
  const size_t i = scene_++;
  if (i >= visits + options_.monkey_scenes.size()) return;
  monkey_ = i >= visits;
  const std::string& path = monkey_ ? options_.monkey_scenes[i - visits] : options_.scenes[i];
  seen_.clear();
  idle_plans_ = 0;
  knobs_again_ = 0;
  scrolls_ = 0;
  set_doing((monkey_ ? "monkey on " : "visiting the widgets of ") + stem(path));
  app_.open_scene(path);
  if (monkey_)
    monkey_left_ = options_.monkey_events;
  else
    ++report_.scenes_visited;
  // Let the new scene's frames draw before the first action.
  queue_.insert(queue_.end(), 2, SyntheticInput{last_pos_});
}

bool SelfTest::plan_visit() {
  const std::vector<ItemRecord>& items = item_log().last();
  const std::string current = stem(app_.scene_path());
  std::set<std::string> scene_stems;
  for (const std::string& f : app_.scene_files()) scene_stems.insert(stem(f));
  const ItemRecord* pick = nullptr;
  // Widgets first, then tabs. A Cancel clicked as soon as it shows would drop the computation
  // whose result carries widgets of its own (Suggest's apply buttons, the substeps' apply
  // buttons): until those were operated it comes last, after them first (it shows only while
  // the work runs).
  const auto seen = [&](const char* label) {
    return std::any_of(report_.visited.begin(), report_.visited.end(),
                       [&](const std::string& v) { return v.find(label) != std::string::npos; });
  };
  // Either apply button of the ceiling and the pair changes a parameter, which drops the
  // result with the other one: after one, two idle frames (the frame drops it), then the
  // button that computes them is pressed again (at most twice a scene) for the other.
  if (knobs_applied_) {
    knobs_applied_ = false;
    if (knobs_again_ < 2 && !(seen("##ceiling'") && seen("'apply alpha, beta'"))) {
      ++knobs_again_;
      for (auto it = seen_.begin(); it != seen_.end();)
        it = it->size() >= 17 && it->compare(it->size() - 17, 17, "|Ceiling and pair") == 0
                 ? seen_.erase(it)
                 : std::next(it);
    }
    queue_.insert(queue_.end(), 2, SyntheticInput{last_pos_});
    return true;
  }
  // The ceiling and the pair are dropped by any parameter change, which other widgets make:
  // once asked for, they are waited for (at most 30 s, then Cancel comes as for the others)
  // and their apply buttons go first.
  if (app_.knobs().busy() && app_.knobs().seconds() < 30) {
    queue_.push_back(SyntheticInput{last_pos_});
    return true;
  }
  // The ceiling and the pair first, at the scene's own parameters (the sliders operated later
  // may leave no stable step to ask about): the Suggest tab, its button, the apply buttons.
  const bool knobs_asked = std::any_of(seen_.begin(), seen_.end(), [](const std::string& k) {
    return k.size() >= 17 && k.compare(k.size() - 17, 17, "|Ceiling and pair") == 0;
  });
  const auto pass_of = [&](const ItemRecord& r) {
    if (!knobs_asked && ((r.kind == ItemKind::tab && r.label.rfind("Suggest", 0) == 0) ||
                         (r.kind == ItemKind::button && r.label == "Ceiling and pair")))
      return 0;
    if (r.kind == ItemKind::button && r.label.find("##ceiling") != std::string::npos)
      return seen("##ceiling'") ? 1 : 0;  // then "apply alpha, beta", drawn after it
    if (r.kind == ItemKind::button &&
        (r.label == "apply alpha, beta" || r.label == "use the paper's step##knobs"))
      return 0;
    if (r.kind == ItemKind::button && r.label == "Cancel") return seen("'apply gamma'") ? 0 : 3;
    if (r.kind == ItemKind::button && r.label == "Cancel##substeps")
      return seen("'apply dt = F/n##exact'") ? 0 : 3;
    if (r.kind == ItemKind::button && r.label == "Cancel##knobs")
      return seen("##ceiling'") ? 0 : 3;
    return r.kind == ItemKind::tab ? 2 : 1;
  };
  for (int pass = 0; pass < 4 && pick == nullptr; ++pass) {
    for (const ItemRecord& r : items) {
      if (!r.enabled || pass_of(r) != pass) continue;
      // The scene list's other entries would leave this scene: its own entry is clicked.
      if (r.kind == ItemKind::selectable && r.label != current && scene_stems.count(r.label) > 0)
        continue;
      if (seen_.count(r.window + "|" + r.label) > 0) continue;
      pick = &r;
      break;
    }
  }
  // Widgets below the fold of the runs' panel (the Suggest tab is long in a small window):
  // the wheel over the panel brings them up, once nothing visible is left to operate or
  // while an apply button of the ceiling and the pair waits below.
  const auto shown = [&](const char* part) {
    return std::any_of(items.begin(), items.end(), [&](const ItemRecord& r) {
      return r.kind == ItemKind::button && r.label.find(part) != std::string::npos;
    });
  };
  bool knob_below = false;
  if (const auto& k = app_.knobs().result(); k && !app_.knobs().busy()) {
    const Params& now = app_.tuner().params();
    knob_below = (with_kappa_ceiling(now, *k) && !seen("##ceiling'") && !shown("##ceiling")) ||
                 (with_rayleigh_pair(now, *k) && !seen("'apply alpha, beta'") &&
                  !shown("apply alpha, beta"));
  }
  if ((pick == nullptr || knob_below) && scrolls_ < 12) {
    if (const auto runs = app_.window_rect("Runs")) {
      ++scrolls_;
      SyntheticInput s{ImVec2(runs->x + 0.5f * runs->w, runs->y + 0.75f * runs->h)};
      s.wheel = -3.0f;
      queue_.push_back(s);
      queue_.push_back(SyntheticInput{s.pos});
      return true;
    }
  }
  if (pick == nullptr) {
    if (++idle_plans_ > 3) return false;
    queue_.insert(queue_.end(), 2, SyntheticInput{last_pos_});  // a popup may still open
    return true;
  }
  idle_plans_ = 0;
  seen_.insert(pick->window + "|" + pick->label);
  if (pick->kind == ItemKind::button && (pick->label.find("##ceiling") != std::string::npos ||
                                         pick->label == "apply alpha, beta" ||
                                         pick->label == "use the paper's step##knobs"))
    knobs_applied_ = pick->label != "use the paper's step##knobs";
  report_.visited.insert(std::string(to_string(pick->kind)) + " '" + pick->label + "' in " +
                         pick->window);
  set_doing(std::string("operating ") + to_string(pick->kind) + " '" + pick->label + "' on " +
            current);
  operate(*pick);
  return true;
}

void SelfTest::operate(const ItemRecord& r) {
  const ImVec2 c = centre(r);
  const float w = r.max.x - r.min.x, h = r.max.y - r.min.y;
  switch (r.kind) {
    case ItemKind::button:
    case ItemKind::checkbox:
    case ItemKind::selectable:
    case ItemKind::tab:
      click(c);
      break;
    case ItemKind::combo:
      click(c);
      if (r.label != "##scene") {  // the scene list's entries are items of their own
        queue_.push_back(SyntheticInput{c});
        click(ImVec2(c.x, r.max.y + 1.5f * ImGui::GetFontSize() + 6.0f));
      }
      break;
    case ItemKind::slider:
      drag(ImVec2(r.min.x + 0.5f * w, c.y), ImVec2(r.min.x + 0.62f * w, c.y));
      break;
    case ItemKind::text_field:
      click(c);
      type("f", true);
      break;
    case ItemKind::number_field:
      click(ImVec2(r.max.x - 0.5f * h, c.y));  // its "+" button
      click(ImVec2(r.min.x + 8.0f, c.y));
      type("7", true);
      break;
    case ItemKind::canvas: {
      drag(ImVec2(c.x - 0.15f * w, c.y - 0.1f * h), ImVec2(c.x + 0.15f * w, c.y + 0.1f * h));
      SyntheticInput wheel{c};
      wheel.wheel = 1.0f;
      queue_.push_back(wheel);
      wheel.wheel = -1.0f;
      queue_.push_back(wheel);
      drag(c, ImVec2(c.x + 10.0f, c.y + 5.0f), true);
      click(c);  // an instant click: down one frame, up the next
      break;
    }
  }
}

void SelfTest::click(ImVec2 p, bool right) {
  SyntheticInput s{p};
  queue_.push_back(s);
  (right ? s.right : s.left) = true;
  queue_.push_back(s);
  (right ? s.right : s.left) = false;
  queue_.push_back(s);
}

void SelfTest::drag(ImVec2 a, ImVec2 b, bool right) {
  SyntheticInput s{a};
  queue_.push_back(s);
  (right ? s.right : s.left) = true;
  queue_.push_back(s);
  s.pos = ImVec2(0.5f * (a.x + b.x), 0.5f * (a.y + b.y));
  queue_.push_back(s);
  s.pos = b;
  queue_.push_back(s);
  (right ? s.right : s.left) = false;
  queue_.push_back(s);
}

void SelfTest::type(const std::string& text, bool enter) {
  for (char ch : text) {
    SyntheticInput s{ImVec2(-1, -1)};
    s.chars = static_cast<unsigned char>(ch);
    queue_.push_back(s);
  }
  if (enter) {
    SyntheticInput s{ImVec2(-1, -1)};
    s.key = ImGuiKey_Enter;
    queue_.push_back(s);
    queue_.push_back(SyntheticInput{ImVec2(-1, -1)});
  }
}

ImVec2 SelfTest::random_point() {
  std::uniform_real_distribution<float> x(0.0f, width_ - 1.0f), y(0.0f, height_ - 1.0f);
  const float px = x(rng_);
  return ImVec2(px, y(rng_));
}

void SelfTest::plan_monkey_event() {
  --monkey_left_;
  ++report_.monkey_events;
  const int r = std::uniform_int_distribution<int>(0, 99)(rng_);
  if (r < 28) {
    click(random_point());
  } else if (r < 34) {
    click(random_point(), true);
  } else if (r < 50) {
    const ImVec2 a = random_point();
    drag(a, random_point());
  } else if (r < 54) {
    const ImVec2 a = random_point();
    drag(a, random_point(), true);
  } else if (r < 72) {
    const std::vector<ItemRecord>& items = item_log().last();
    if (items.empty()) {
      click(random_point());
    } else {
      const ItemRecord& it =
          items[std::uniform_int_distribution<size_t>(0, items.size() - 1)(rng_)];
      click(centre(it));
    }
  } else if (r < 80) {
    SyntheticInput s{random_point()};
    s.wheel = static_cast<float>(std::uniform_int_distribution<int>(-3, 3)(rng_));
    queue_.push_back(s);
  } else if (r < 90) {
    SyntheticInput s{ImVec2(-1, -1)};
    s.key = kMonkeyKeys[std::uniform_int_distribution<size_t>(0, std::size(kMonkeyKeys) - 1)(rng_)];
    queue_.push_back(s);
    queue_.push_back(SyntheticInput{ImVec2(-1, -1)});
  } else {
    SyntheticInput s{ImVec2(-1, -1)};
    s.chars = static_cast<unsigned char>(
        kMonkeyChars[std::uniform_int_distribution<size_t>(0, sizeof(kMonkeyChars) - 2)(rng_)]);
    queue_.push_back(s);
  }
}

}  // namespace dampbound::ui
