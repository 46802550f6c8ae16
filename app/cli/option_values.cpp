#include "cli/option_values.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <limits>

#include <CLI/CLI.hpp>

#include "image/picture_file.h"
#include "scene/reader_support.h"

namespace bounce {
namespace {

bool parse_double(std::string_view text, double& value) {
  // from_chars has no leading '+'; accept it like strtod does.
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

std::string format_g(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

}  // namespace

// CLI11's PositiveNumber and Range let NaN and infinities through and print
// DBL_MAX in full (309 digits); this prints limits with %g.

CLI::Validator number_in(double lo, double hi, bool lo_open, bool hi_open) {
  const bool unbounded = std::isinf(hi);
  const std::string range =
      unbounded ? std::string(lo_open ? "> " : ">= ") + format_g(lo)
                : std::string(lo_open ? "(" : "[") + format_g(lo) + ", " + format_g(hi) + (hi_open ? ")" : "]");
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0.0;
        if (!parse_double(text, v)) return "'" + text + "' is not a finite number";
        if (v < lo || (lo_open && v == lo) || v > hi || (hi_open && v == hi))
          return format_g(v) + " is out of range: must be " + (unbounded ? range : "in " + range);
        return {};
      },
      unbounded ? range : "in " + range);
}

CLI::Validator count_at_most(std::uint64_t most) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        std::string_view digits = text;
        if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
        std::uint64_t v = 0;
        auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
        if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size())
          return "'" + text + "' is not a whole number from 0 to " + std::to_string(most);
        if (v > most) return text + " is out of range: must be at most " + std::to_string(most);
        return {};
      },
      most == std::numeric_limits<std::uint64_t>::max() ? ">= 0" : "0 to " + std::to_string(most));
}

CLI::Validator vec3_value() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const auto v = parse_vec3(text);
        if (!v) return "expected x,y,z (three finite numbers), got '" + text + "'";
        for (int i = 0; i < 3; ++i)
          if (std::abs((*v)[i]) > max_file_number)
            return "coordinate " + format_g((*v)[i]) + " is out of range (limit " + format_g(max_file_number) +
                   " in magnitude)";
        return {};
      },
      "x,y,z");
}

CLI::Validator image_size_value() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const auto size = parse_size(text);
        if (!size) return "expected WxH (two whole numbers), got '" + text + "'";
        return check_image_size(size->first, size->second);
      },
      "WxH");
}

std::optional<vec3> parse_vec3(const std::string& text) {
  vec3 v;
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    std::size_t comma = text.find(',', start);
    bool last = i == 2;
    if (last != (comma == std::string::npos)) return std::nullopt;
    std::string_view part = std::string_view(text).substr(start, last ? std::string::npos : comma - start);
    if (!parse_double(part, v[i])) return std::nullopt;
    start = comma + 1;
  }
  return v;
}

std::optional<std::pair<int, int>> parse_size(const std::string& text) {
  std::size_t x = text.find('x');
  if (x == std::string::npos) return std::nullopt;
  int w = 0, h = 0;
  auto [e1, c1] = std::from_chars(text.data(), text.data() + x, w);
  auto [e2, c2] = std::from_chars(text.data() + x + 1, text.data() + text.size(), h);
  if (c1 != std::errc() || e1 != text.data() + x || c2 != std::errc() || e2 != text.data() + text.size())
    return std::nullopt;
  return std::pair{w, h};
}

std::string check_image_size(long long width, long long height) {
  if (width < 1 || height < 1 || width > max_image_side || height > max_image_side)
    return "size " + std::to_string(width) + "x" + std::to_string(height) + " must be from 1 to " +
           std::to_string(max_image_side) + " pixels per side";
  if (width * height > max_image_pixels)
    return "size " + std::to_string(width) + "x" + std::to_string(height) + " has " + std::to_string(width * height) +
           " pixels, more than the limit of " + std::to_string(max_image_pixels) + " (" +
           std::to_string(max_image_side) + "x" + std::to_string(max_image_pixels / max_image_side) + ")";
  return {};
}

std::string given_options(const CLI::App& command, std::span<const char* const> names) {
  std::string list;
  for (const char* name : names)
    if (command.count(name) > 0) list += std::string(list.empty() ? "" : ", ") + name;
  return list;
}

namespace {

// The file a path names, symbolic links followed as far as they exist.
std::filesystem::path resolved(const std::string& path) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  return ec ? std::filesystem::absolute(path).lexically_normal() : p;
}

}  // namespace

std::string check_output_files(std::initializer_list<output_file> files) {
  for (const output_file& f : files)
    if (!f.path.empty())
      if (std::string e = check_output_path(f.option, f.path, f.picture); !e.empty()) return e;
  for (auto a = files.begin(); a != files.end(); ++a)
    for (auto b = std::next(a); b != files.end(); ++b)
      if (!a->path.empty() && !b->path.empty() && resolved(a->path) == resolved(b->path))
        return std::string(a->option) + " " + a->path + " and " + b->option + " " + b->path +
               " name the same file: give each output its own";
  return {};
}

std::string check_outputs_against_inputs(const std::vector<output_file>& outputs,
                                         const std::vector<std::string>& inputs) {
  for (const output_file& out : outputs) {
    if (out.path.empty()) continue;
    const std::filesystem::path target = resolved(out.path);
    for (const std::string& in : inputs)
      if (resolved(in) == target)
        return std::string(out.option) + " " + out.path + " would overwrite " + in +
               ", which the scene is read from: choose another name";
  }
  return {};
}

std::string check_png_only(const CLI::App& command, std::initializer_list<const char*> options,
                           const std::string& out_path) {
  if (!is_linear(picture_format_of(out_path).value_or(picture_format::png))) return {};
  for (const char* png_only : options)
    if (command.count(png_only))
      return std::string(png_only) + " applies to PNG output only (--out " + out_path + " is linear radiance)";
  return {};
}

}  // namespace bounce
