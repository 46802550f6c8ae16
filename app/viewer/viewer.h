// `bounce view`: the GLFW window with the Gouraud view, the ImGui panel
// and the solver running on its own thread.
#pragma once

#include <string>
#include <vector>

#include "radiosity/solver_settings.h"
#include "scene/scene.h"

namespace bounce {

struct viewer_options {
  int frames = 0;               // > 0: a scripted run of this many frames (tests)
  std::string screenshot_path;  // written after the last scripted frame
  bool screenshot_panel = true;
  bool exit_after = false;      // leave after the scripted frames
  bool start_paused = false;    // mesh and show the scene, shoot nothing until Start
  int msaa = -1;                // window samples; -1: 4 on GPUs, 0 on software GL (llvmpipe)
  double exposure = 0.0;        // > 0: this exposure, fixed; 0: automatic (exposure_control.h)
  std::string still_path;       // scripted run: trace a still (scene camera's size) halfway, wait, save it as PNG
  bool error_plot = false;      // path trace a reference at the start and plot the solution's error against it
  std::string screenshots_dir;  // scripted run: the view (no panel) every `screenshot_every` frames, as PNGs
  int screenshot_every = 0;
  bool refine_at_rest = true;              // --no-refine-at-rest: the live Gouraud view only
  int refined_passes = 0;                  // scripted run: the last frame waits until the view shows this many passes
  std::vector<std::string> load_warnings;  // the scene's, from loading it: the panel's import report
};

// Returns an exit code; without a display it says so and returns 1.
int run_viewer(const scene& s, const solver_settings& solver, const viewer_options& options);

}  // namespace bounce
