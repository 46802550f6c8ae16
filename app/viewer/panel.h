// The ImGui control panel. Draws from the worker's published view and the
// panel's own settings; returns what the user asked for, which the window
// (or the headless render) carries out. No solver internals here.
#pragma once

#include <string>
#include <vector>

#include "error_tracker.h"
#include "mesh_renderer.h"
#include "radiosity/solver_settings.h"
#include "solver_worker.h"

namespace bounce {

// Settings of the ray-traced still that the panel starts.
struct still_settings {
  int integrator = 0;       // 0: Whitted two-pass, 1: path tracer (reference)
  int spp = 4;              // samples per pixel
  int direct = 0;           // Whitted: 0 direct light by shadow rays, 1 all diffuse light from the solution
  bool window_size = true;  // trace at the window's size, else at `size`
  int size[2] = {0, 0};     // width, height; 0: the scene camera's
  std::string png_path = "bounce-still.png";
  std::string pfm_path = "bounce-still.pfm";
};

// What the window tells the panel about the still.
struct still_status {
  bool running = false;
  double progress = 0.0;  // 0..1
  unsigned texture = 0;   // GL texture of the last finished still, 0: none yet
  int width = 0, height = 0;
  std::string summary;
};

struct panel_state {
  std::string scene_path;
  std::vector<std::string> asset_scenes;  // offered in a list
  solver_settings solver;                 // mesh density, method and its settings, criterion
  gl::display_settings display;
  bool screenshot_with_panel = false;
  std::string screenshot_path = "bounce-screenshot.png";
  still_settings still;
  bool show_help = false;
  std::string message;  // last action's result, e.g. where a screenshot went
};

struct panel_actions {
  bool open_scene = false;  // load panel_state::scene_path
  bool apply_mesh = false;  // re-mesh the current scene with the panel's solver settings
  bool pause = false, resume = false, step = false, restart = false;
  bool screenshot = false;
  bool frame_scene = false, reset_camera = false;
  bool trace_still = false, cancel_still = false, save_still_png = false, save_still_pfm = false;
  bool compute_reference = false;  // path trace a reference of the camera for the error plot
  bool set_stop = false;           // the stopping point changed: the running solver takes it
};

// Draws the panel into the current ImGui frame. `frame_ms` is the last
// frame's time, shown with the statistics.
panel_actions draw_panel(panel_state& state, const worker_view& view, double frame_ms, const still_status& still = {},
                         const error_status& errors = {});

// The solver setting a run is remembered under: method, its parameter,
// element size and stopping point.
std::string setting_key(const solver_settings& settings);

// The keyboard shortcuts, shown in the help popup and handled by the window.
const std::vector<std::pair<std::string, std::string>>& shortcuts();

// Scenes under a folder (assets/*/*.json), for the panel's list.
std::vector<std::string> find_scenes(const std::string& folder);

}  // namespace bounce
