// The `bounce` command line: subcommands, the option sets they share, and
// the parsing of option values. One parser for every command.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "radiosity/solver_settings.h"
#include "scene/scene.h"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace bounce {

// Camera overrides of every command that renders, as typed.
struct camera_options {
  std::string file;  // --camera: a camera file, loaded before the other overrides apply
  std::string eye, target, up, size;
  std::optional<double> fov;
};

// The options of every command that solves (solve, render, trace, view)
// set the core's solver settings directly.
void add_solver_options(CLI::App& command, solver_settings& settings);
void add_camera_options(CLI::App& command, camera_options& options);

// Limits of the command line. Pictures: at most this per side (as a scene
// file's camera) and this many pixels in all. Exposure: radiance up to the
// scene files' limit (1e9) times the largest exposure stays within float.
inline constexpr int max_image_side = 16384;
inline constexpr long long max_image_pixels = 16384LL * 2048;  // 32 Mpixel: a 384 MiB float picture
inline constexpr double min_exposure = 1e-9, max_exposure = 1e9;

// An error message when a picture of width x height breaks those limits,
// else an empty string.
std::string check_image_size(long long width, long long height);

// The names of the options add_solver_options adds, and those of `names`
// given on `command`'s line ("--a, --b"), for messages about options that
// a combination ignores.
std::span<const char* const> solver_option_names();
std::string given_options(const CLI::App& command, std::span<const char* const> names);

// The check of every floating-point option: a finite number in [lo, hi]
// (an open end when `*_open`; hi may be infinite), its limits printed with
// %g. (CLI11's PositiveNumber and Range let NaN through.)
CLI::Validator number_in(double lo, double hi, bool lo_open = false, bool hi_open = false);

// Solver options that the chosen form-factor method ignores; an error
// message or an empty string.
std::string check_solver_options(const CLI::App& command, solver_settings& settings);

// Parses "x,y,z" and "WxH"; on failure returns nullopt.
std::optional<vec3> parse_vec3(const std::string& text);
std::optional<std::pair<int, int>> parse_size(const std::string& text);

// Applies the overrides to `view`; returns an error message naming the
// option at fault, or an empty string.
std::string apply_camera_options(const camera_options& options, camera& view);

// Exit codes of `bounce`.
enum exit_code : int {
  exit_ok = 0,
  exit_input_error = 1,  // a scene or file that cannot be used
  exit_usage = 2,        // bad command line
};

// Loads the scene named on a command line (empty: the embedded Cornell box)
// and applies the camera overrides (null: none); prints the warnings, then
// any error, and returns its exit code (exit_ok when loaded).
int load_for_command(const std::string& path, const camera_options* camera_overrides, scene& s);

int run_cli(int argc, char** argv);

}  // namespace bounce
