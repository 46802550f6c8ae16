// `bounce render`: solve, then draw the Gouraud view headlessly (OSMesa)
// with the same renderer as the window, and write PNG / PFM files.
#pragma once

#include <string>

#include "cli.h"

namespace bounce {

struct render_options {
  std::string png_path = "bounce.png";  // --out
  std::string pfm_path;                 // --pfm: linear radiance
  std::string frames_dir;               // --frames: one PNG per `frame_every` shots
  long frame_every = 1;
  double exposure = 1.0;
  std::string curve = "srgb";  // srgb | filmic
  bool wireframe = false;
  bool ambient = false;
  bool panel = false;                // draw the ImGui panel over the view, as the window shows it
  std::string colours = "radiance";  // radiance | unshot | size (false colour)
  std::string stats_path;            // --stats: solver statistics as JSON
};

int run_render(const scene& s, const solver_settings& solver, const render_options& options);

}  // namespace bounce
