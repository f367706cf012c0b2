// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// An RGB8 image in memory (rows top first, as a PNG stores them) and PNG
// output through stb_image_write. Everything the renderer produces — frames
// and plots — ends up as one of these.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace dda::render {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

// A rectangle of pixels: columns x .. x+w-1, rows y .. y+h-1 (row 0 at the top).
struct PixelRect {
  int x = 0, y = 0, w = 0, h = 0;
  int right() const { return x + w; }   // one past the last column
  int bottom() const { return y + h; }  // one past the last row
  bool contains(int px, int py) const { return px >= x && px < x + w && py >= y && py < y + h; }
  bool empty() const { return w <= 0 || h <= 0; }
};

class Image {
 public:
  Image() = default;
  Image(int width, int height, Rgb fill = {255, 255, 255});

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ <= 0 || height_ <= 0; }

  // (0, 0) is the top-left pixel. Reads out of range are an internal error;
  // writes out of range are ignored (drawing code clips by doing nothing).
  Rgb pixel(int x, int y) const;
  void set_pixel(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
    std::uint8_t* p = &rgb_[(static_cast<std::size_t>(y) * width_ + x) * 3];
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
  }
  // Mixes `c` over the pixel with coverage `alpha` in [0, 1].
  void blend_pixel(int x, int y, Rgb c, float alpha);
  void fill_rect(const PixelRect& r, Rgb c);
  void fill(Rgb c) { fill_rect({0, 0, width_, height_}, c); }

  // Packed RGB8, 3·width bytes a row, top row first.
  std::uint8_t* data() { return rgb_.data(); }
  const std::uint8_t* data() const { return rgb_.data(); }
  std::size_t size_bytes() const { return rgb_.size(); }

  friend bool operator==(const Image&, const Image&) = default;

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> rgb_;
};

// PNG bytes of the image (stb_image_write; fixed zlib level and row filter,
// chosen for speed — see image.cpp).
std::vector<std::uint8_t> encode_png(const Image& image);

// Writes the image as a PNG file. The file appears whole or not at all (it is
// written beside the target and renamed). Throws dda::Error naming the path
// and the system's reason when the file cannot be written; the parent folder
// must exist.
void write_png(const Image& image, const std::filesystem::path& path);

}  // namespace dda::render
