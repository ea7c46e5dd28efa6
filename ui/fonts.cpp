#include "ui/fonts.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

namespace dampbound::ui {

namespace {

/// Glyphs beyond Basic Latin the app uses: Latin-1 (x, degree), Greek (gamma, kappa),
/// punctuation (dashes, bullet), super/subscripts, arrows, maths operators (<=, infinity).
/// ImGui keeps the pointer, so the array is static.
const ImWchar kGlyphRanges[] = {
    0x0020, 0x00FF, 0x0370, 0x03FF, 0x2010, 0x2027, 0x2070, 0x209F,
    0x2190, 0x21FF, 0x2200, 0x22FF, 0,
};

/// The title font of the atlas it belongs to (title_font() checks the atlas is current).
struct TitleFontSlot {
  ImFontAtlas* atlas = nullptr;
  ImFont* font = nullptr;
};
TitleFontSlot g_title;

/// Reads a whole file into memory owned by ImGui's allocator (the atlas frees it).
void* read_ttf(const std::string& path, int& size) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return nullptr;
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 12 || bytes.size() > (64u << 20)) return nullptr;
  void* mem = ImGui::MemAlloc(bytes.size());
  std::memcpy(mem, bytes.data(), bytes.size());
  size = static_cast<int>(bytes.size());
  return mem;
}

ImFont* add_ttf(const std::string& path, float size_px) {
  int size = 0;
  void* data = read_ttf(path, size);
  if (data == nullptr) return nullptr;
  ImFontConfig cfg;
  cfg.FontDataOwnedByAtlas = true;
  cfg.OversampleH = 2;
  cfg.OversampleV = 1;
  return ImGui::GetIO().Fonts->AddFontFromMemoryTTF(data, size, size_px, &cfg, kGlyphRanges);
}

}  // namespace

FontOptions default_font_options() { return FontOptions{}; }

LoadedFonts load_fonts(const FontOptions& options) {
  ImGuiIO& io = ImGui::GetIO();
  LoadedFonts fonts;
  if (options.prefer_ttf && !options.ttf_path.empty()) {
    fonts.body = add_ttf(options.ttf_path, options.size_px);
    if (fonts.body != nullptr) {
      const float title_px = std::round(options.size_px * options.title_scale);
      if (!options.title_ttf_path.empty()) fonts.title = add_ttf(options.title_ttf_path, title_px);
      if (fonts.title == nullptr) fonts.title = add_ttf(options.ttf_path, title_px);
      if (fonts.title == nullptr) fonts.title = fonts.body;
      fonts.ttf = true;
    }
  }
  if (fonts.body == nullptr) {
    // ProggyClean is a 13 px bitmap font: scale it by a whole factor so it stays crisp.
    ImFontConfig cfg;
    cfg.SizePixels = 13.0f;
    fonts.body = io.Fonts->AddFontDefault(&cfg);
    fonts.title = fonts.body;
    io.FontGlobalScale = std::max(1.0f, std::round(options.size_px / 13.0f));
  }
  io.FontDefault = fonts.body;
  g_title = {io.Fonts, fonts.title};
  return fonts;
}

ImFont* title_font() {
  if (ImGui::GetCurrentContext() != nullptr && g_title.atlas == ImGui::GetIO().Fonts &&
      g_title.font != nullptr) {
    return g_title.font;
  }
  return ImGui::GetFont();
}

void apply_theme(Theme theme, float size_px) {
  ImGuiStyle& style = ImGui::GetStyle();
  style = ImGuiStyle();
  if (theme == Theme::Dark) {
    ImGui::StyleColorsDark(&style);
  } else {
    ImGui::StyleColorsLight(&style);
  }
  style.WindowRounding = 4.0f;
  style.FrameRounding = 3.0f;
  if (size_px > 13.0f) style.ScaleAllSizes(size_px / 13.0f);
}

bool current_theme_is_dark() {
  const ImVec4 c = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z < 0.5f;
}

}  // namespace dampbound::ui
