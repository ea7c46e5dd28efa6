// ui/image.hpp: pixel access, blank detection, PNG round trip, atomic write errors. No GL.
#include "ui/image.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace dampbound::ui {
namespace {

Image checker(int w, int h) {
  Image img;
  img.width = w;
  img.height = h;
  img.rgba.resize(static_cast<size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      uint8_t* p = &img.rgba[(static_cast<size_t>(y) * w + x) * 4];
      p[0] = static_cast<uint8_t>(x * 10);
      p[1] = static_cast<uint8_t>(y * 10);
      p[2] = (x + y) % 2 == 0 ? 255 : 0;
      p[3] = 255;
    }
  }
  return img;
}

TEST(Image, PixelAndBlank) {
  Image img = checker(4, 3);
  EXPECT_EQ(img.pixel(2, 1), (Rgba{20, 10, 0, 255}));
  EXPECT_FALSE(is_blank(img));
  Image flat;
  flat.width = 3;
  flat.height = 2;
  flat.rgba.assign(24, 7);
  EXPECT_TRUE(is_blank(flat));
  EXPECT_TRUE(is_blank(Image{}));
  EXPECT_TRUE(has_color_near(img, 0, 0, 1, Rgba{10, 10, 255, 255}, 0));
  EXPECT_FALSE(has_color_near(img, 0, 0, 0, Rgba{10, 10, 255, 255}, 0));
  EXPECT_EQ(count_color(img, Rgba{0, 0, 255, 255}, 0), 1);
}

TEST(Image, RgbaFromPackedColour) {
  // IM_COL32(R, G, B, A) = A << 24 | B << 16 | G << 8 | R
  EXPECT_EQ(rgba_from_u32(0x80402010u), (Rgba{0x10, 0x20, 0x40, 0x80}));
}

TEST(Image, PngRoundTripIsAtomic) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "dampbound_image_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "checker.png").string();
  const Image img = checker(17, 9);
  write_png_atomic(img, path);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  const Image back = read_png(path);
  EXPECT_EQ(back.width, 17);
  EXPECT_EQ(back.height, 9);
  EXPECT_EQ(back.rgba, img.rgba);
}

TEST(Image, WriteFailureNamesThePath) {
  const std::string path = "/nonexistent-dir-dampbound/x.png";
  try {
    write_png_atomic(checker(2, 2), path);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  EXPECT_THROW(write_png_atomic(Image{}, "/tmp/empty.png"), std::runtime_error);
  EXPECT_THROW(read_png("/nonexistent-dir-dampbound/x.png"), std::runtime_error);
}

}  // namespace
}  // namespace dampbound::ui
