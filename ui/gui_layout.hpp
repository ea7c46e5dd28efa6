#pragma once
// The tuner window's layout: the default place of each panel for a window size (compact
// below kCompactLayoutHeight), panels following a resize, and ImGui::Begin at those places.
// The geometry needs no ImGui context (tests/ui/gui_layout_test.cpp); begin() does.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dampbound::ui {

/// Below this window height (pixels) the layout is compact: the parameters take the whole
/// left column (they need about 560 px, 62 % of the height) and the Status and Criteria tabs
/// join the runs' tabs.
constexpr float kCompactLayoutHeight = 900.0f;

/// A panel's place: name, position and size in pixels.
struct PanelRect {
  std::string name;
  float x, y, w, h;
};

/// True when a window `height` pixels high takes the compact layout.
bool compact_layout(float height);

/// The default layout for a width x height window (pixels): controls on the left, the mesh
/// and the envelope on top, the displacement and the runs below. The panels tile the window.
std::vector<PanelRect> default_layout(float width, float height);

/// Where the `drawn` panels go when the window changes from `from` to `to` (w, h pixels): a
/// panel still where the default layout of `from` put it takes the default layout of `to`,
/// one the user moved or resized keeps its place and size in proportion.
std::vector<PanelRect> panels_after_resize(const std::vector<PanelRect>& drawn, float from_w,
                                           float from_h, float to_w, float to_h);

/// The panels an imgui.ini remembers: each [Window][name] section with its Pos=x,y and
/// Size=w,h (pixels); sections without both, and lines that do not parse, are skipped, and a
/// later section of the same name wins (as ImGui loads it).
std::vector<PanelRect> remembered_panels(const std::string& imgui_ini);

/// The layout state across frames. Remembered positions (imgui.ini) win over the default
/// layout unless a reset was asked; on a resize every panel follows (panels_after_resize).
class GuiLayout {
 public:
  /// Lays out a width x height frame (pixels); call before the first begin() of the frame.
  void update(float width, float height);
  /// The window size the remembered panels (imgui.ini) were laid out in.
  void set_remembered_size(float width, float height);
  /// The remembered panels themselves (remembered_panels): each is placed there, by the
  /// program, at its first begin(). ImGui hides a new window for one frame unless its size is
  /// set that way, so without this the first frame of every start after the first was blank.
  void set_remembered_panels(std::vector<PanelRect> panels) { remembered_ = std::move(panels); }
  /// ImGui::Begin of panel `name` at its place; records where it was drawn.
  bool begin(const char* name, int flags);
  /// Asks for the default layout at the next frame ("Reset layout").
  void request_reset() { reset_ = true; }
  /// Call after the last panel of a frame.
  void end_frame() { reset_ = false; }
  /// True when this frame's layout is compact (the Status panel is not drawn).
  bool compact() const { return compact_; }
  /// Where panel `name` was drawn in the last frame.
  std::optional<PanelRect> drawn(const std::string& name) const;

 private:
  std::vector<PanelRect> default_;   ///< the default layout of this frame's size
  std::vector<PanelRect> follow_;    ///< where panels go this frame after a resize
  std::vector<PanelRect> drawn_;     ///< where each panel was last drawn
  std::vector<PanelRect> remembered_;  ///< imgui.ini's panels not yet begun
  std::vector<std::string> hidden_;  ///< panels not drawn in this layout (compact: Status)
  float laid_w_ = 0, laid_h_ = 0;    ///< the window size drawn_ was laid out in (pixels)
  bool reset_ = false;
  bool compact_ = false;
};

}  // namespace dampbound::ui
