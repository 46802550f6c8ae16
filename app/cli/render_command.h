// `bounce render`: solve, then draw the Gouraud view headlessly (OSMesa)
// with the same renderer as the window, and write PNG / PFM files.
#pragma once

#include <string>

#include "cli/camera_options.h"
#include "radiosity/solver_settings.h"
#include "scene/scene.h"

namespace CLI {
class App;
}  // namespace CLI

namespace bounce {

struct render_options {
  std::string scene;                    // SCENE; empty: the embedded Cornell box
  solver_settings solver;               // the solver options
  bool view_independent = false;        // --view-independent: the camera does not lead refinement
  camera_options camera;                // the camera overrides
  std::string out_path = "bounce.png";  // --out: the extension picks the format
  std::string pfm_path;                 // --pfm: also linear radiance
  std::string frames_dir;               // --frames: PNGs of the convergence
  long frame_every = 0;                 // steps between frames; 0: after 1, 2, 4, 8, ... steps
  double exposure = 1.0;
  std::string curve = "srgb";  // srgb | filmic
  bool wireframe = false;
  bool ambient = false;
  bool panel = false;                // draw the ImGui panel over the view, as the window shows it
  std::string colours = "radiance";  // radiance | remaining | size (false colour)
  std::string stats_path;            // --stats: solver statistics as JSON
  int msaa = 4;                      // samples per pixel; 0 or 1: none
};

void add_render_options(CLI::App& command, render_options& options);

// Combinations that would ignore an option (solver options, options of
// PNG output with a linear --out), and output paths that cannot be
// written; an error message or an empty string. May settle the solver the
// options choose (check_solver_options).
std::string check_render_options(const CLI::App& command, render_options& options);

// Loads the options' scene with their camera, then renders it.
int run_render(const render_options& options);

// Solves `s` with the options' solver and renders its camera's view; the
// options' scene and camera are not read (`bounce SCENE` without a display
// renders a scene it has loaded).
int render_scene(const scene& s, const render_options& options);

}  // namespace bounce
