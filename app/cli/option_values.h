// The values the commands' options take, checked and parsed once for every
// command: finite numbers in a range, counts, x,y,z and WxH, the limits of
// pictures and exposure, and the output files' checks. A check returns an
// error message, or an empty string when the value is fine.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "scene/scene.h"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace bounce {

// Limits of the command line. Pictures: at most this per side (as a scene
// file's camera) and this many pixels in all. Exposure: radiance up to the
// scene files' limit (1e9) times the largest exposure stays within float.
inline constexpr int max_image_side = 16384;
inline constexpr long long max_image_pixels = 16384LL * 2048;  // 32 Mpixel: a 384 MiB float picture
inline constexpr double min_exposure = 1e-9, max_exposure = 1e9;

// An error message when a picture of width x height breaks those limits,
// else an empty string.
std::string check_image_size(long long width, long long height);

// The check of every floating-point option: a finite number in [lo, hi]
// (an open end when `*_open`; hi may be infinite), its limits printed with
// %g. (CLI11's PositiveNumber and Range let NaN through.)
CLI::Validator number_in(double lo, double hi, bool lo_open = false, bool hi_open = false);

// A count: digits only (CLI11 reads "-1" into an unsigned as 2^64 - 1), at most `most`.
CLI::Validator count_at_most(std::uint64_t most);

// --eye, --target, --up: three finite numbers, each at most the scene
// files' limit in magnitude. --size: WxH within the limits above.
CLI::Validator vec3_value();
CLI::Validator image_size_value();

// Parses "x,y,z" and "WxH"; on failure returns nullopt.
std::optional<vec3> parse_vec3(const std::string& text);
std::optional<std::pair<int, int>> parse_size(const std::string& text);

// The names of `names` given on `command`'s line ("--a, --b"), for
// messages about options that a combination ignores.
std::string given_options(const CLI::App& command, std::span<const char* const> names);

// A file a command writes, checked before any long work starts. An empty
// path is not asked for and passes.
struct output_file {
  const char* option;  // "--out"
  std::string path;
  bool picture = false;  // its extension must name a picture format
};
// Each output's folder exists and can be written, its file too if it
// exists, its extension fits, and no two outputs name the same file (after
// symbolic links).
std::string check_output_files(std::initializer_list<output_file> files);

// After loading: no output names a file the scene was read from (the
// scene, its MTL, textures, buffers: load_report::inputs), after symbolic
// links. An error message or an empty string.
std::string check_outputs_against_inputs(const std::vector<output_file>& outputs,
                                         const std::vector<std::string>& inputs);

// Options of tone-mapped (PNG) output given while --out `out_path` names a
// linear format: the first of `options` given, in a message, or an empty
// string.
std::string check_png_only(const CLI::App& command, std::initializer_list<const char*> options,
                           const std::string& out_path);

}  // namespace bounce
