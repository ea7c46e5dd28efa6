#pragma once
// The tuner's widgets, each an ImGui call that also notes the item it drew (kind, label, window,
// rectangle on screen, enabled) in the frame's item log when the log is on: `gui --self-test`
// (ui/gui_self_test.hpp) reads it to find and operate every widget. Scoped push/pop helpers: each
// push is undone by its object's destructor, on every path out of the scope.
#include <imgui.h>

#include <string>
#include <vector>

namespace dampbound::ui {

/// What an item is, for the self-test's choice of how to operate it.
enum class ItemKind {
  button,
  checkbox,
  slider,
  combo,
  selectable,
  text_field,
  number_field,
  tab,
  canvas
};

/// "button", "checkbox", ... (the self-test's report).
const char* to_string(ItemKind kind);

/// One widget as drawn in a frame.
struct ItemRecord {
  ItemKind kind = ItemKind::button;
  std::string label;   ///< the ImGui label, "##id" part included
  std::string window;  ///< the ImGui window it sits in (a popup's own name for combo lists)
  ImVec2 min, max;     ///< its rectangle clipped to the window's visible area (pixels)
  bool enabled = true;
};

/// The items of the frame being built and of the last finished one. Off by default: the log
/// costs nothing then.
class ItemLog {
 public:
  bool on = false;
  /// Ends the frame being built: its items become last().
  void end_frame();
  const std::vector<ItemRecord>& last() const { return last_; }
  /// Notes the item ImGui just drew (nothing when the log is off or the item is clipped away).
  void note(ItemKind kind, const char* label);

 private:
  std::vector<ItemRecord> building_, last_;
};

/// The process's item log (one tuner window per process).
ItemLog& item_log();

/// The widgets the tuner uses, as ImGui's of the same name plus a note in item_log().
namespace item {
bool button(const char* label, const ImVec2& size = ImVec2(0, 0));
bool small_button(const char* label);
bool checkbox(const char* label, bool* v);
bool slider_double(const char* label, double* v, double lo, double hi, const char* format,
                   ImGuiSliderFlags flags = 0);
bool slider_int(const char* label, int* v, int lo, int hi, const char* format,
                ImGuiSliderFlags flags = 0);
bool slider_float(const char* label, float* v, float lo, float hi, const char* format);
bool begin_combo(const char* label, const char* preview);
bool combo(const char* label, int* current, const char* const items[], int count);
bool combo(const char* label, int* current, const char* items_zero_separated);
bool combo(const char* label, int* current, bool (*getter)(void*, int, const char**), void* data,
           int count);
bool selectable(const char* label, bool selected);
bool input_text(const char* label, std::string* text, ImGuiInputTextFlags flags = 0);
bool input_text_hint(const char* label, const char* hint, std::string* text,
                     ImGuiInputTextFlags flags = 0);
bool input_int(const char* label, int* v, int step, int step_fast);
bool input_double(const char* label, double* v, double step, double step_fast, const char* format);
bool begin_tab_item(const char* label, ImGuiTabItemFlags flags);
bool invisible_button(const char* id, const ImVec2& size, ImGuiButtonFlags flags = 0);
}  // namespace item

/// PushStyleColor on construction, PopStyleColor on destruction; `when` false: neither.
class ScopedStyleColor {
 public:
  ScopedStyleColor(ImGuiCol idx, const ImVec4& color, bool when = true);
  ScopedStyleColor(ImGuiCol idx, ImU32 color, bool when = true);
  ~ScopedStyleColor();
  ScopedStyleColor(const ScopedStyleColor&) = delete;
  ScopedStyleColor& operator=(const ScopedStyleColor&) = delete;

 private:
  bool pushed_;
};

/// BeginDisabled(disabled) / EndDisabled().
class ScopedDisabled {
 public:
  explicit ScopedDisabled(bool disabled);
  ~ScopedDisabled();
  ScopedDisabled(const ScopedDisabled&) = delete;
  ScopedDisabled& operator=(const ScopedDisabled&) = delete;
};

/// PushID(int) / PopID().
class ScopedID {
 public:
  explicit ScopedID(int id);
  ~ScopedID();
  ScopedID(const ScopedID&) = delete;
  ScopedID& operator=(const ScopedID&) = delete;
};

/// PushItemWidth(width) / PopItemWidth().
class ScopedItemWidth {
 public:
  explicit ScopedItemWidth(float width);
  ~ScopedItemWidth();
  ScopedItemWidth(const ScopedItemWidth&) = delete;
  ScopedItemWidth& operator=(const ScopedItemWidth&) = delete;
};

}  // namespace dampbound::ui
