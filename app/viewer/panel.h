// The ImGui control panel. Draws from the worker's published view and the
// panel's own settings; returns what the user asked for, which the window
// (or the headless render) carries out. No solver internals here.
#pragma once

#include <string>
#include <vector>

#include "cli.h"
#include "mesh_renderer.h"
#include "solver_worker.h"

namespace bounce {

struct panel_state {
  std::string scene_path;
  std::vector<std::string> asset_scenes;  // offered in a list
  solver_options solver;                  // mesh density, method and its settings, criterion
  gl::display_settings display;
  bool screenshot_with_panel = false;
  std::string screenshot_path = "bounce-screenshot.png";
  bool show_help = false;
  std::string message;  // last action's result, e.g. where a screenshot went
};

struct panel_actions {
  bool open_scene = false;  // load panel_state::scene_path
  bool apply_mesh = false;  // re-mesh the current scene with the panel's solver settings
  bool pause = false, resume = false, step = false, restart = false;
  bool screenshot = false;
  bool frame_scene = false, reset_camera = false;
};

// Draws the panel into the current ImGui frame. `frame_ms` is the last
// frame's time, shown with the statistics.
panel_actions draw_panel(panel_state& state, const worker_view& view, double frame_ms);

// The keyboard shortcuts, shown in the help popup and handled by the window.
const std::vector<std::pair<std::string, std::string>>& shortcuts();

// Scenes under a folder (assets/*/*.json), for the panel's list.
std::vector<std::string> find_scenes(const std::string& folder);

}  // namespace bounce
