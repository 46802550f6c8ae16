#include "scene/reader_support.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <stb/stb_image.h>

#include "base/embedded.h"

namespace bounce {
namespace {

constexpr std::string_view embedded_prefix = "embedded:";

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace

namespace {
thread_local input_log* current_log = nullptr;
}  // namespace

input_log::input_log() : outer_(current_log) {
  current_log = this;
}

input_log::~input_log() {
  current_log = outer_;
}

void note_input_file(const std::string& path) {
  if (current_log && path.rfind(embedded_prefix, 0) != 0) current_log->files.push_back(path);
}

std::optional<std::string> read_file(const std::string& path) {
  note_input_file(path);
  if (path.rfind(embedded_prefix, 0) == 0) {
    std::string_view name = std::string_view(path).substr(embedded_prefix.size());
    for (const embedded_file& f : embedded_files())
      if (f.path == name) return std::string(f.contents);
    return std::nullopt;
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

std::string resolve(const std::string& base_file, const std::string& relative) {
  std::filesystem::path rel(relative);
  if (rel.is_absolute()) return relative;
  return (std::filesystem::path(base_file).parent_path() / rel).lexically_normal().string();
}

texture read_image_texture(const std::string& path, const std::string& name, const std::string& where) {
  std::optional<std::string> bytes = read_file(path);
  if (!bytes) throw load_error(where + ": cannot read texture '" + path + "'");
  return decode_image_texture(*bytes, name, where, "texture '" + path + "'");
}

texture decode_image_texture(std::string_view bytes, const std::string& name, const std::string& where,
                             const std::string& what) {
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                                                static_cast<int>(bytes.size()), &w, &h, &channels, 4);
  if (!pixels) throw load_error(where + ": cannot decode " + what + ": " + stbi_failure_reason());
  texture t;
  t.name = name;
  t.kind = texture_kind::image;
  t.width = w;
  t.height = h;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  t.texels.resize(n * 3);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) t.texels[3 * i + c] = static_cast<float>(srgb_to_linear(pixels[4 * i + c] / 255.0));
  // Coverage is linear; kept only where the image has it (grey + alpha, RGBA).
  if (channels == 2 || channels == 4) {
    t.alpha.resize(n);
    for (std::size_t i = 0; i < n; ++i) t.alpha[i] = pixels[4 * i + 3] / 255.0f;
  }
  stbi_image_free(pixels);
  return t;
}

std::string json_parse_reason(std::string reason) {
  constexpr std::size_t kept = 40;
  const std::string marker = "last read: '";
  if (const std::size_t at = reason.find(marker); at != std::string::npos) {
    const std::size_t start = at + marker.size();
    std::size_t end = reason.find("'; ", start);  // what follows the quote, if anything
    if (end == std::string::npos) end = reason.size() - (reason.ends_with("'") ? 1 : 0);
    if (end - start > kept) reason.replace(start, end - start - kept, "...");
  }
  for (char& c : reason)
    if (static_cast<unsigned char>(c) >= 0x80) c = '?';  // the parser's reason may quote broken UTF-8
  return one_line(std::move(reason), 300);
}

std::string one_line(std::string text, std::size_t longest) {
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  if (text.size() > longest) text = text.substr(0, longest / 2) + " ... " + text.substr(text.size() - longest / 2);
  return text;
}

std::string format_value(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

std::string format_value(const rgb& c) {
  return c.r == c.g && c.g == c.b ? format_value(c.r)
                                  : format_value(c.r) + " " + format_value(c.g) + " " + format_value(c.b);
}

}  // namespace bounce
