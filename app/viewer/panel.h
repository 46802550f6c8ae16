// The ImGui control panel. Draws from the worker's published view and the
// panel's own settings; returns what the user asked for, which the window
// (or the headless render) carries out. No solver internals here.
#pragma once

#include <string>
#include <vector>

#include "radiosity/solver_settings.h"
#include "render/mesh_renderer.h"
#include "scene/warning_groups.h"
#include "viewer/error_tracker.h"
#include "viewer/solver_worker.h"

namespace bounce {

// Settings of the ray-traced still that the panel starts.
struct still_settings {
  int integrator = 0;       // 0: Whitted two-pass, 1: twopass, 2: ppm, 3: path tracer (still_params)
  int spp = 4;              // samples per pixel
  int direct = 0;           // Whitted: 0 direct light by shadow rays, 1 all diffuse light from the solution
  bool window_size = true;  // trace at the window's size, else at `size`
  int size[2] = {0, 0};     // width, height; 0: the scene camera's
  std::string png_path;     // empty: a new name for each save (dated_file_name)
  std::string pfm_path;
};

// What the window tells the panel about the still.
struct still_status {
  bool running = false;
  double progress = 0.0;  // 0..1
  unsigned texture = 0;   // GL texture of the last finished still, 0: none yet
  int width = 0, height = 0;
  std::string summary;
};

// Where the panel stands: docked at the window's right edge, full height,
// the view taking the rest of the window (Blender's sidebar). Remembered
// between runs (user_files.h).
struct panel_layout {
  bool visible = true;   // Tab or F1 hides it: the view takes the whole window
  float width = 400.0f;  // in the window's coordinates; dragged by its left edge
};

// The docked panel's width in a window `window_width` wide: 0 when hidden,
// else layout.width kept between 300 and what leaves the view 160 wide.
float docked_width(const panel_layout& layout, float window_width);

// A named camera kept for a scene.
struct camera_bookmark {
  std::string name;
  camera view;
};

struct panel_state {
  panel_layout layout;
  std::string scene_path;
  std::vector<std::string> asset_scenes;   // offered in a list
  std::vector<std::string> recent_scenes;  // most recent first
  solver_settings solver;                  // mesh density, method and its settings, criterion
  gl::display_settings display;
  bool auto_exposure = true;  // the window sets display.exposure from the picture (exposure_control.h)
  bool screenshot_with_panel = false;
  std::string screenshot_path;  // empty: a new name for each screenshot (dated_file_name)
  std::string bake_path;        // "Bake to file": empty, a new .glb for each (dated_file_name)
  still_settings still;
  camera current_camera;                   // the window's camera this frame (the window sets it)
  std::vector<camera_bookmark> bookmarks;  // of the scene shown
  std::string camera_path = "bounce-camera.json";
  bool show_help = false;
  bool show_still = false;    // the still's window; closed by its X or Esc, opened by a new still
  bool confirm_quit = false;  // the "quit while working?" popup
  std::string message;        // last action's result, e.g. where a screenshot went: at the panel's top
  std::string still_message;  // the still window's saves, shown in that window
  std::string warning;        // about the scene as seen (back faces), shown under the errors
  // The import report: the groups of the shown scene's load warnings
  // (made once per scene), and the warnings last seen with the section open
  // (others are "new").
  std::shared_ptr<const std::vector<std::string>> warnings_grouped, warnings_read;
  std::vector<warning_group> warning_groups;
  bool refine_at_rest = true;  // refine the view towards the still while the camera rests
  int refined_passes = 0;      // passes of that refinement shown now (the window sets it)
};

struct panel_actions {
  bool open_scene = false;  // load panel_state::scene_path
  // Solve the current scene again with the panel's solver settings
  // (re-meshed if they mesh it otherwise): Apply, a new solver or link tolerance.
  bool apply_mesh = false;
  bool pause = false, resume = false, step = false, restart = false;
  bool screenshot = false;
  bool bake = false;  // write the shown solution for other tools (bake_action.h)
  bool frame_scene = false, reset_camera = false;
  bool trace_still = false, cancel_still = false, save_still_png = false, save_still_pfm = false;
  bool compute_reference = false;  // path trace a reference of the camera for the error plot
  bool cancel_reference = false;   // stop the reference being traced
  bool set_stop = false;           // the stopping point changed: the running solver takes it
  bool set_view = false;           // panel_state::solver.view changed: the running solver is led by it
  bool quit = false;               // close the window
  bool save_camera = false;        // write current_camera to camera_path
  bool add_bookmark = false;       // keep current_camera as a new bookmark
  int go_to_bookmark = -1;         // index into bookmarks, or -1
  int delete_bookmark = -1;        // index into bookmarks, or -1
  bool save_layout = false;        // the panel was resized or hidden: remember its layout
};

// The camera as the command line's options, to paste after `bounce render`
// or `bounce trace`: "--eye x,y,z --target x,y,z --up x,y,z --fov f --size WxH".
std::string camera_command_line(const camera& view);

// Esc, as people expect it: it closes what is open first (the help, the
// quit question, the still's window), and quits only when nothing is;
// while the solver or a still is working, it asks first. Ctrl+Q quits at
// once (handle_input).
panel_actions escape(panel_state& state, bool working);

// Draws the panel into the current ImGui frame. `frame_ms` is the last
// frame's time, shown with the statistics.
panel_actions draw_panel(panel_state& state, const worker_view& view, double frame_ms, const still_status& still = {},
                         const error_status& errors = {});

// The solver setting a run is remembered under: solver, its method and
// parameter, element size and stopping point.
std::string setting_key(const solver_settings& settings);

// The panel's solver choice: the settings take the solver, and a solver
// other than the one chosen restarts the solve with it (apply_mesh).
panel_actions choose_solver(panel_state& state, solver_method method);

// The settings a run is started with from the panel's: the hierarchical
// solver meshes once, so adaptive meshing (progressive only) is left out;
// the panel keeps it for when the progressive solver is chosen again.
solver_settings settings_to_run(const solver_settings& panel_settings);

// What the actions ask of the solver (open, apply, stopping point, pause,
// resume, step, restart), sent to the worker as the window does.
void send_to_worker(const panel_actions& act, const panel_state& state, solver_worker& worker);

// What the run shown is doing: "converged" (its stopping point holds),
// "refining links" (the hierarchical solver under its stopping point,
// refining links towards the final tolerance), "solving" or "paused".
std::string run_state(const worker_view& view);

// The statistics of the run shown, one line each: the hierarchical
// solver's steps, residual and links, or the progressive solver's shots
// and unshot power.
std::vector<std::string> statistics_lines(const worker_view& view, double frame_ms);

// A tolerance as the panel shows it: "1e-5", "2.5e-6".
std::string format_tolerance(double value);

// A fraction as a percentage, three significant digits: "100%", "0.1%", "2.5e-5%".
std::string format_percent(double fraction);

// The keyboard shortcuts, shown in the help popup and handled by the window.
const std::vector<std::pair<std::string, std::string>>& shortcuts();

// Scenes under a folder (assets/*/*.json), for the panel's list.
std::vector<std::string> find_scenes(const std::string& folder);

}  // namespace bounce
