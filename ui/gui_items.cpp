#include "ui/gui_items.hpp"

#include <imgui_internal.h>
#include <imgui_stdlib.h>

namespace dampbound::ui {

const char* to_string(ItemKind kind) {
  switch (kind) {
    case ItemKind::button:
      return "button";
    case ItemKind::checkbox:
      return "checkbox";
    case ItemKind::slider:
      return "slider";
    case ItemKind::combo:
      return "combo";
    case ItemKind::selectable:
      return "combo entry";
    case ItemKind::text_field:
      return "text field";
    case ItemKind::number_field:
      return "number field";
    case ItemKind::tab:
      return "tab";
    case ItemKind::canvas:
      return "canvas";
  }
  return "?";
}

void ItemLog::end_frame() {
  last_.swap(building_);
  building_.clear();
}

void ItemLog::note(ItemKind kind, const char* label) {
  if (!on) return;
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  const ImGuiWindow* w = g.CurrentWindow;
  ImRect r = g.LastItemData.Rect;
  r.ClipWith(w->ClipRect);
  if (r.GetWidth() < 2.0f || r.GetHeight() < 2.0f) return;  // scrolled out of sight
  ItemRecord rec;
  rec.kind = kind;
  rec.label = label;
  rec.window = w->Name;
  rec.min = r.Min;
  rec.max = r.Max;
  rec.enabled = (g.LastItemData.InFlags & ImGuiItemFlags_Disabled) == 0;
  building_.push_back(std::move(rec));
}

ItemLog& item_log() {
  static ItemLog log;
  return log;
}

namespace item {
namespace {
template <class R>
R noted(ItemKind kind, const char* label, R r) {
  item_log().note(kind, label);
  return r;
}
}  // namespace

bool button(const char* label, const ImVec2& size) {
  return noted(ItemKind::button, label, ImGui::Button(label, size));
}
bool small_button(const char* label) {
  return noted(ItemKind::button, label, ImGui::SmallButton(label));
}
bool checkbox(const char* label, bool* v) {
  return noted(ItemKind::checkbox, label, ImGui::Checkbox(label, v));
}
bool slider_double(const char* label, double* v, double lo, double hi, const char* format,
                   ImGuiSliderFlags flags) {
  return noted(ItemKind::slider, label,
               ImGui::SliderScalar(label, ImGuiDataType_Double, v, &lo, &hi, format, flags));
}
bool slider_int(const char* label, int* v, int lo, int hi, const char* format,
                ImGuiSliderFlags flags) {
  return noted(ItemKind::slider, label, ImGui::SliderInt(label, v, lo, hi, format, flags));
}
bool slider_float(const char* label, float* v, float lo, float hi, const char* format) {
  return noted(ItemKind::slider, label, ImGui::SliderFloat(label, v, lo, hi, format));
}
bool begin_combo(const char* label, const char* preview) {
  // Open, the popup is the current window and its entries follow: the combo itself was noted
  // in the frames before, closed.
  const bool open = ImGui::BeginCombo(label, preview);
  if (!open) item_log().note(ItemKind::combo, label);
  return open;
}
// Open, ImGui::Combo leaves the popup's data as the last item: the combo is noted closed only.
bool combo(const char* label, int* current, const char* const items[], int count) {
  const ImGuiID id = ImGui::GetID(label);
  const bool changed = ImGui::Combo(label, current, items, count);
  if (ImGui::GetItemID() == id) item_log().note(ItemKind::combo, label);
  return changed;
}
bool combo(const char* label, int* current, const char* items_zero_separated) {
  const ImGuiID id = ImGui::GetID(label);
  const bool changed = ImGui::Combo(label, current, items_zero_separated);
  if (ImGui::GetItemID() == id) item_log().note(ItemKind::combo, label);
  return changed;
}
bool combo(const char* label, int* current, bool (*getter)(void*, int, const char**), void* data,
           int count) {
  const ImGuiID id = ImGui::GetID(label);
  const bool changed = ImGui::Combo(label, current, getter, data, count);
  if (ImGui::GetItemID() == id) item_log().note(ItemKind::combo, label);
  return changed;
}
bool selectable(const char* label, bool selected) {
  return noted(ItemKind::selectable, label, ImGui::Selectable(label, selected));
}
bool input_text(const char* label, std::string* text, ImGuiInputTextFlags flags) {
  return noted(ItemKind::text_field, label, ImGui::InputText(label, text, flags));
}
bool input_text_hint(const char* label, const char* hint, std::string* text,
                     ImGuiInputTextFlags flags) {
  return noted(ItemKind::text_field, label, ImGui::InputTextWithHint(label, hint, text, flags));
}
bool input_int(const char* label, int* v, int step, int step_fast) {
  return noted(ItemKind::number_field, label, ImGui::InputInt(label, v, step, step_fast));
}
bool input_double(const char* label, double* v, double step, double step_fast, const char* format) {
  return noted(ItemKind::number_field, label,
               ImGui::InputDouble(label, v, step, step_fast, format));
}
bool begin_tab_item(const char* label, ImGuiTabItemFlags flags) {
  return noted(ItemKind::tab, label, ImGui::BeginTabItem(label, nullptr, flags));
}
bool invisible_button(const char* id, const ImVec2& size, ImGuiButtonFlags flags) {
  return noted(ItemKind::canvas, id, ImGui::InvisibleButton(id, size, flags));
}
}  // namespace item

ScopedStyleColor::ScopedStyleColor(ImGuiCol idx, const ImVec4& color, bool when) : pushed_(when) {
  if (pushed_) ImGui::PushStyleColor(idx, color);
}
ScopedStyleColor::ScopedStyleColor(ImGuiCol idx, ImU32 color, bool when) : pushed_(when) {
  if (pushed_) ImGui::PushStyleColor(idx, color);
}
ScopedStyleColor::~ScopedStyleColor() {
  if (pushed_) ImGui::PopStyleColor();
}
ScopedDisabled::ScopedDisabled(bool disabled) {
  ImGui::BeginDisabled(disabled);
}
ScopedDisabled::~ScopedDisabled() {
  ImGui::EndDisabled();
}
ScopedID::ScopedID(int id) {
  ImGui::PushID(id);
}
ScopedID::~ScopedID() {
  ImGui::PopID();
}
ScopedItemWidth::ScopedItemWidth(float width) {
  ImGui::PushItemWidth(width);
}
ScopedItemWidth::~ScopedItemWidth() {
  ImGui::PopItemWidth();
}

}  // namespace dampbound::ui
