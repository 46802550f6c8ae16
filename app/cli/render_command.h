// `bounce render`: solve, then draw the Gouraud view headlessly (OSMesa)
// with the same renderer as the window, and write PNG / PFM files.
#pragma once

#include <string>

#include "cli/cli.h"

namespace bounce {

struct render_options {
  std::string out_path = "bounce.png";  // --out: the extension picks the format
  std::string pfm_path;                 // --pfm: also linear radiance
  std::string frames_dir;               // --frames: PNGs of the convergence
  long frame_every = 0;                 // shots between frames; 0: after 1, 2, 4, 8, ... shots
  double exposure = 1.0;
  std::string curve = "srgb";  // srgb | filmic
  bool wireframe = false;
  bool ambient = false;
  bool panel = false;                // draw the ImGui panel over the view, as the window shows it
  std::string colours = "radiance";  // radiance | unshot | size (false colour)
  std::string stats_path;            // --stats: solver statistics as JSON
  int msaa = 4;                      // samples per pixel; 0 or 1: none
};

int run_render(const scene& s, const solver_settings& solver, const render_options& options);

}  // namespace bounce
