// Images: linear float RGB in memory; PNG (8-bit sRGB) and PFM (linear
// float, unscaled) on disk.
#pragma once

#include <string>
#include <vector>

#include "base/math_types.h"

namespace bounce {

// Linear RGB, row 0 at the top.
struct image {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;  // width * height * 3
  rgb at(int x, int y) const {
    const std::size_t i = (std::size_t(y) * width + x) * 3;
    return {pixels[i], pixels[i + 1], pixels[i + 2]};
  }
};

// A width x height picture of one value.
inline image uniform_image(int width, int height, rgb value) {
  image img;
  img.width = width;
  img.height = height;
  img.pixels.reserve(std::size_t(width) * std::size_t(height) * 3);
  for (int i = 0; i < width * height; ++i)
    for (int c = 0; c < 3; ++c) img.pixels.push_back(float(value[c]));
  return img;
}

// 8-bit RGB(A) rows, row 0 at the top, written as PNG. Returns false with
// `error` naming the file.
// stb_image_write's write function into a std::string (its `context`):
// pictures are encoded in memory, then written whole (base/whole_file.h),
// every write checked, which stb's own file writers do not do.
void append_bytes(void* to, void* data, int size);

bool write_png(const std::string& path, int width, int height, int channels, const unsigned char* rows,
               std::string& error);

// Linear radiance x exposure as 8-bit sRGB rows (no alpha), for write_png.
std::vector<unsigned char> to_srgb_rows(const image& img, double exposure);

// Portable float map (little-endian "PF"), linear radiance, rows stored
// bottom-up as the format says.
bool write_pfm(const std::string& path, const image& img, std::string& error);
bool read_pfm(const std::string& path, image& img, std::string& error);

// Reads a PNG (or any stb-supported file) as 8-bit RGB, row 0 at the top.
bool read_png_rgb8(const std::string& path, int& width, int& height, std::vector<unsigned char>& rgb8,
                   std::string& error);

}  // namespace bounce
