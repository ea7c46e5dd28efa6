#include "ui/image.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "core/io/files.hpp"

namespace dampbound::ui {

Rgba rgba_from_u32(uint32_t c) {
  return {static_cast<uint8_t>(c & 0xFFu), static_cast<uint8_t>((c >> 8) & 0xFFu),
          static_cast<uint8_t>((c >> 16) & 0xFFu), static_cast<uint8_t>((c >> 24) & 0xFFu)};
}

Rgba Image::pixel(int x, int y) const {
  const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4;
  return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
}

std::string encode_png(const Image& img) {
  if (img.empty() || img.rgba.size() != static_cast<size_t>(img.width) * img.height * 4)
    throw std::runtime_error("cannot encode a PNG: the image is empty or malformed");
  std::string bytes;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<size_t>(size));
  };
  if (stbi_write_png_to_func(append, &bytes, img.width, img.height, 4, img.rgba.data(),
                             img.width * 4) == 0)
    throw std::runtime_error("cannot encode a PNG: stb_image_write failed");
  return bytes;
}

void write_png_atomic(const Image& img, const std::string& path) {
  // Encoded in memory first: stb's file writer does not report a failed write (a full
  // disk gave a truncated PNG); the core writer checks every byte.
  write_file_bytes(path, encode_png(img));
}

Image read_png(const std::string& path) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 4);
  if (data == nullptr) {
    const char* why = stbi_failure_reason();
    throw std::runtime_error("cannot read image " + path + ": " + (why != nullptr ? why : "unknown error"));
  }
  Image img;
  img.width = w;
  img.height = h;
  img.rgba.assign(data, data + static_cast<size_t>(w) * h * 4);
  stbi_image_free(data);
  return img;
}

bool is_blank(const Image& img) {
  if (img.empty()) return true;
  const uint8_t* p = img.rgba.data();
  for (size_t i = 4; i + 3 < img.rgba.size(); i += 4) {
    if (std::memcmp(p, p + i, 4) != 0) return false;
  }
  return true;
}

namespace {
bool close_rgb(const Rgba& p, const Rgba& c, int tol) {
  return std::abs(p.r - c.r) <= tol && std::abs(p.g - c.g) <= tol && std::abs(p.b - c.b) <= tol;
}
}  // namespace

bool has_color_near(const Image& img, int x, int y, int radius, Rgba color, int tolerance) {
  for (int yy = y - radius; yy <= y + radius; ++yy) {
    for (int xx = x - radius; xx <= x + radius; ++xx) {
      if (xx < 0 || yy < 0 || xx >= img.width || yy >= img.height) continue;
      if (close_rgb(img.pixel(xx, yy), color, tolerance)) return true;
    }
  }
  return false;
}

long count_color(const Image& img, Rgba color, int tolerance) {
  long n = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) n += close_rgb(img.pixel(x, y), color, tolerance) ? 1 : 0;
  }
  return n;
}

}  // namespace dampbound::ui
