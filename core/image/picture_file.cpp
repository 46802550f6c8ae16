#include "image/picture_file.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>

#include <stb/stb_image_write.h>
#include <tinyexr.h>
#include <unistd.h>

#include "base/whole_file.h"

namespace bounce {

std::optional<picture_format> picture_format_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".png") return picture_format::png;
  if (ext == ".pfm") return picture_format::pfm;
  if (ext == ".exr") return picture_format::exr;
  if (ext == ".hdr") return picture_format::hdr;
  return std::nullopt;
}

bool is_linear(picture_format format) {
  return format != picture_format::png;
}

const char* picture_extensions() {
  return ".png, .pfm, .exr or .hdr";
}

std::string check_output_path(const std::string& option, const std::string& path, bool picture) {
  namespace fs = std::filesystem;
  if (path.empty()) return option + ": the file name is empty";
  std::error_code ec;
  if (fs::is_directory(path, ec)) return option + " " + path + ": is a folder, not a file";
  if (picture && !picture_format_of(path))
    return option + " " + path + ": unknown picture format '" + fs::path(path).extension().string() + "' (use " +
           picture_extensions() + ")";
  const fs::path folder = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
  if (!fs::is_directory(folder, ec)) return option + " " + path + ": the folder " + folder.string() + " does not exist";
  if (::access(folder.c_str(), W_OK) != 0)
    return option + " " + path + ": the folder " + folder.string() + " is not writable";
  if (fs::exists(path, ec) && ::access(path.c_str(), W_OK) != 0)
    return option + " " + path + ": the file is not writable";
  // Outputs are written beside and renamed over the old file: a device or
  // a pipe would be replaced, not written to.
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
    return option + " " + path + ": not a regular file (a device, a pipe, a socket): name a file";
  return {};
}

bool write_exr(const std::string& path, const image& img, std::string& error) {
  // Encoded in memory, then written whole: tinyexr's own file writer does
  // not check its close. Channels are stored B, G, R (the order most
  // readers expect), as half floats: 11 bits of mantissa, ample for radiance.
  const std::size_t count = std::size_t(img.width) * std::size_t(img.height);
  std::vector<float> planes[3];
  for (int c = 0; c < 3; ++c) {
    planes[c].resize(count);
    for (std::size_t i = 0; i < count; ++i) planes[c][i] = img.pixels[3 * i + std::size_t(c)];
  }
  float* bgr[3] = {planes[2].data(), planes[1].data(), planes[0].data()};
  EXRImage exr;
  InitEXRImage(&exr);
  exr.num_channels = 3;
  exr.images = reinterpret_cast<unsigned char**>(bgr);
  exr.width = img.width;
  exr.height = img.height;
  EXRHeader header;
  InitEXRHeader(&header);
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
  header.num_channels = 3;
  std::vector<EXRChannelInfo> channels(3);
  for (int c = 0; c < 3; ++c) channels[std::size_t(c)].name[0] = "BGR"[c];
  header.channels = channels.data();
  int pixel_types[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
  int stored_types[3] = {TINYEXR_PIXELTYPE_HALF, TINYEXR_PIXELTYPE_HALF, TINYEXR_PIXELTYPE_HALF};
  header.pixel_types = pixel_types;
  header.requested_pixel_types = stored_types;
  unsigned char* memory = nullptr;
  const char* message = nullptr;
  const std::size_t size = SaveEXRImageToMemory(&exr, &header, &memory, &message);
  if (size == 0) {
    error = path + ": cannot encode OpenEXR: " + (message ? std::string(message) : "unknown reason");
    if (message) FreeEXRErrorMessage(message);
    return false;
  }
  const std::string bytes(reinterpret_cast<const char*>(memory), size);
  std::free(memory);
  return write_file(path, bytes, error);
}

bool write_hdr(const std::string& path, const image& img, std::string& error) {
  std::string bytes;
  if (!stbi_write_hdr_to_func(append_bytes, &bytes, img.width, img.height, 3, img.pixels.data())) {
    error = path + ": cannot encode Radiance HDR";
    return false;
  }
  return write_file(path, bytes, error);
}

bool write_picture(const std::string& path, const image& img, double exposure, std::string& error) {
  const std::optional<picture_format> format = picture_format_of(path);
  if (!format) {
    error = path + ": unknown picture format (use " + std::string(picture_extensions()) + ")";
    return false;
  }
  switch (*format) {
    case picture_format::png: {
      const std::vector<unsigned char> rows = to_srgb_rows(img, exposure);
      return write_png(path, img.width, img.height, 3, rows.data(), error);
    }
    case picture_format::pfm:
      return write_pfm(path, img, error);
    case picture_format::exr:
      return write_exr(path, img, error);
    case picture_format::hdr:
      return write_hdr(path, img, error);
  }
  return false;
}

}  // namespace bounce
