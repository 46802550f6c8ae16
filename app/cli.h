// The `bounce` command line: subcommands, the option sets they share, and
// the parsing of option values. One parser for every command.
#pragma once

#include <optional>
#include <string>

#include "scene.h"

namespace CLI {
class App;
}

namespace bounce {

// Options of every command that solves (solve, render, trace, view).
struct solver_options {
  std::string method = "raycast";  // raycast | hemicube
  double max_edge = 0.0;           // element size in scene units; 0 = scene default
  double until = 0.01;             // stop when unshot power falls below this fraction
  long max_shots = 0;              // 0 = no limit
  double seconds = 0.0;            // wall-time limit; 0 = none
  double patch_edge = -1.0;        // shooter size (substructuring); 0 = elements shoot; < 0 = 4 x max edge
  int shadow_rays = 16;            // raycast: rays per receiver-shooter pair
  bool full_rays = false;          // raycast: every ray for every pair, no 2x2 probe
  int hemicube_resolution =
      128;                 // hemicube: pixels along the top face (README "Speed against error": 256 bought nothing)
  std::string stats_path;  // --stats FILE.json
  bool adaptive = false;   // adaptive meshing (a priori and a posteriori)
  double tolerance = 0.5;  // adaptive: relative radiosity difference that splits an element
  double min_edge = 0.0;   // adaptive: shortest edge a split may make; 0 = max edge / 8
};

// Camera overrides of every command that renders, as typed.
struct camera_options {
  std::string eye, target, up, size;
  std::optional<double> fov;
};

void add_solver_options(CLI::App& command, solver_options& options);

struct radiosity_params;
struct mesher_params;
struct stop_criterion;
// The core parameters the options stand for.
radiosity_params to_radiosity_params(const solver_options& options);
// Resolves the defaults that depend on the scene (element and patch size).
mesher_params to_mesher_params(const solver_options& options, const scene& s);
stop_criterion to_stop_criterion(const solver_options& options);
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
