// `bounce view`: the command line of the interactive window. The window
// itself is the viewer's (viewer/viewer.h); this reads its options.
#pragma once

#include <string>

#include "cli/camera_options.h"
#include "radiosity/solver_settings.h"
#include "viewer/viewer.h"

namespace CLI {
class App;
}  // namespace CLI

namespace bounce {

struct view_options {
  std::string scene;              // SCENE; empty: the embedded Cornell box
  solver_settings solver;         // the solver options
  camera_options camera;          // the camera overrides
  viewer_options window;          // scripted runs, screenshots, start paused, ...
  bool view_independent = false;  // --view-independent: the window's camera does not lead the solver
};

void add_view_options(CLI::App& command, view_options& options);

// Solver options the chosen solver ignores, and output paths that cannot
// be written; an error message or an empty string.
std::string check_view_options(const CLI::App& command, view_options& options);

// Loads the options' scene with their camera and opens the window on it.
int run_view(const view_options& options);

}  // namespace bounce
