#include "image/image.h"

#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "base/whole_file.h"
#include "image/tonemap.h"

namespace bounce {

void append_bytes(void* to, void* data, int size) {
  static_cast<std::string*>(to)->append(static_cast<const char*>(data), std::size_t(size));
}

bool write_png(const std::string& path, int width, int height, int channels, const unsigned char* rows,
               std::string& error) {
  std::string bytes;
  if (!stbi_write_png_to_func(append_bytes, &bytes, width, height, channels, rows, width * channels)) {
    error = path + ": cannot encode PNG";
    return false;
  }
  return write_file(path, bytes, error);
}

std::vector<unsigned char> to_srgb_rows(const image& img, double exposure) {
  std::vector<unsigned char> rows(std::size_t(img.width) * img.height * 3);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const glm::u8vec3 c = to_srgb8(img.at(x, y), exposure);
      const std::size_t i = (std::size_t(y) * img.width + x) * 3;
      rows[i] = c.r;
      rows[i + 1] = c.g;
      rows[i + 2] = c.b;
    }
  return rows;
}

bool write_pfm(const std::string& path, const image& img, std::string& error) {
  static_assert(std::endian::native == std::endian::little, "PFM writer assumes a little-endian machine");
  return write_whole(
      path,
      [&](const std::string& file, std::string& reason) {
        std::ofstream out(file, std::ios::binary);
        if (!out) {
          reason = "cannot open for writing: " + system_reason("unknown reason");
          return false;
        }
        out << "PF\n" << img.width << " " << img.height << "\n-1.0\n";  // negative scale: little-endian
        for (int y = img.height - 1; y >= 0; --y)
          out.write(reinterpret_cast<const char*>(&img.pixels[std::size_t(y) * img.width * 3]),
                    std::streamsize(sizeof(float) * 3 * img.width));
        out.close();
        if (!out) reason = "write failed: " + system_reason("unknown reason");
        return bool(out);
      },
      error);
}

bool read_pfm(const std::string& path, image& img, std::string& error) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    error = path + (std::filesystem::exists(path, ec) ? ": not a file" : ": no such file");
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot read: " + std::strerror(errno);
    return false;
  }
  std::string magic;
  double scale = 0.0;
  int w = 0, h = 0;
  if (!(in >> magic >> w >> h >> scale) || magic != "PF" || w <= 0 || h <= 0 || w > 65536 || h > 65536 ||
      scale >= 0.0) {
    error = path + ": not a little-endian colour PFM";
    return false;
  }
  in.get();  // the single whitespace after the header
  // The pixels the header promises must be in the file, before any is
  // allocated: a header may claim 65536 x 65536 over a few bytes.
  const std::uint64_t needed = std::uint64_t(w) * std::uint64_t(h) * 3 * sizeof(float);
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec || std::uint64_t(in.tellg()) + needed > size) {
    error = path + ": truncated PFM: its header says " + std::to_string(w) + "x" + std::to_string(h) + " (" +
            std::to_string(needed) + " bytes of pixels), the file has " + std::to_string(size) + " bytes";
    return false;
  }
  img.width = w;
  img.height = h;
  img.pixels.assign(std::size_t(w) * h * 3, 0.0f);
  for (int y = h - 1; y >= 0; --y)
    if (!in.read(reinterpret_cast<char*>(&img.pixels[std::size_t(y) * w * 3]),
                 std::streamsize(sizeof(float) * 3 * w))) {
      error = path + ": truncated PFM";
      return false;
    }
  return true;
}

bool read_png_rgb8(const std::string& path, int& width, int& height, std::vector<unsigned char>& rgb8,
                   std::string& error) {
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &width, &height, &channels, 3);
  if (!data) {
    error = path + ": cannot read image: " + stbi_failure_reason();
    return false;
  }
  rgb8.assign(data, data + std::size_t(width) * height * 3);
  stbi_image_free(data);
  return true;
}

}  // namespace bounce
