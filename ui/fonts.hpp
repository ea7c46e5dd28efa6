#pragma once
// Fonts and theme for both hosts. ImGui's built-in 13 px ProggyClean is too small for a
// 1200x700 figure, so DejaVu Sans (Debian package fonts-dejavu-core) is loaded when present,
// at a body size and a larger title size; without it the built-in font is used, scaled.
#include <imgui.h>

#include <string>

namespace dampbound::ui {

/// Light (figures, white background) or dark (the interactive GUI) colours.
enum class Theme { Light, Dark };

/// How fonts are chosen. Sizes in pixels.
struct FontOptions {
  float size_px = 16.0f;      ///< body text (ticks, legend, panels)
  float title_scale = 1.3f;   ///< title font = size_px * title_scale
  bool prefer_ttf = true;     ///< false: always the built-in font
  std::string ttf_path = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  /// Title face; when missing the body face is used at the title size.
  std::string title_ttf_path = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf";
};

/// Defaults: 16 px DejaVu Sans, titles 1.3x in DejaVu Sans Bold.
FontOptions default_font_options();

/// Fonts loaded into the current ImGui context's atlas.
struct LoadedFonts {
  ImFont* body = nullptr;   ///< also the default font of the context
  ImFont* title = nullptr;  ///< larger; equals body with the built-in font
  bool ttf = false;         ///< true when the TTF file was used
};

/// Loads the fonts into ImGui::GetIO().Fonts (call after ImGui::CreateContext and before the
/// first frame), makes body the default, and remembers title for title_font(). A missing or
/// unreadable TTF falls back to the built-in font scaled to about size_px; never throws.
LoadedFonts load_fonts(const FontOptions& options);

/// The title font loaded by load_fonts() for the current context, else the current font.
ImFont* title_font();

/// Applies the theme's ImGui colours and scales paddings/rounding for size_px.
void apply_theme(Theme theme, float size_px);

/// True when the current ImGui style looks dark (window background luminance < 0.5).
bool current_theme_is_dark();

}  // namespace dampbound::ui
