#pragma once
// RGBA images read back from the GL hosts, PNG output, and the pixel checks the render tests
// use. No GL here.
#include <cstdint>
#include <string>
#include <vector>

namespace dampbound::ui {

/// One 8-bit RGBA pixel.
struct Rgba {
  uint8_t r = 0, g = 0, b = 0, a = 0;
  bool operator==(const Rgba& o) const { return r == o.r && g == o.g && b == o.b && a == o.a; }
  bool operator!=(const Rgba& o) const { return !(*this == o); }
};

/// The Rgba of a packed ImU32 colour (IM_COL32 layout: R in the low byte, A in the high byte).
Rgba rgba_from_u32(uint32_t color);

/// 8-bit RGBA pixels, rows from the top, 4 * width bytes per row, no padding.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;

  /// Pixel at column x, row y (0, 0 = top left). Precondition: inside the image.
  Rgba pixel(int x, int y) const;
  bool empty() const { return width <= 0 || height <= 0 || rgba.empty(); }
};

/// `img` as PNG bytes (stb_image_write). Throws std::runtime_error for an empty image.
std::string encode_png(const Image& img);

/// Writes `img` as a PNG through core's one output writer (core/io/files.hpp: whole or not at all,
/// only a regular file). Throws InputError naming the path when it cannot.
void write_png_atomic(const Image& img, const std::string& path);

/// Reads a PNG (or any format stb_image reads) as RGBA. Throws std::runtime_error naming the
/// path when it cannot.
Image read_png(const std::string& path);

/// True when every pixel has the same colour (an empty image counts as blank).
bool is_blank(const Image& img);

/// True when some pixel within `radius` (Chebyshev distance) of (x, y) matches `color` in
/// R, G and B to within `tolerance` per channel.
bool has_color_near(const Image& img, int x, int y, int radius, Rgba color, int tolerance = 8);

/// Number of pixels matching `color` in R, G and B to within `tolerance` per channel.
long count_color(const Image& img, Rgba color, int tolerance = 8);

}  // namespace dampbound::ui
