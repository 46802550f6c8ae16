// The `bounce` command line: subcommands, the option sets they share, and
// the parsing of option values. One parser for every command.
#pragma once

#include <optional>
#include <string>

#include "scene.h"
#include "solver_settings.h"

namespace CLI {
class App;
}

namespace bounce {

// Camera overrides of every command that renders, as typed.
struct camera_options {
  std::string eye, target, up, size;
  std::optional<double> fov;
};

// The options of every command that solves (solve, render, trace, view)
// set the core's solver settings directly.
void add_solver_options(CLI::App& command, solver_settings& settings);
void add_camera_options(CLI::App& command, camera_options& options);

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

int run_cli(int argc, char** argv);

}  // namespace bounce
