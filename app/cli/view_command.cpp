#include "cli/view_command.h"

#include <CLI/CLI.hpp>

#include "cli/option_values.h"
#include "cli/scene_argument.h"
#include "cli/solver_options.h"
#include "common/exit_code.h"

namespace bounce {

void add_view_options(CLI::App& command, view_options& options) {
  add_scene_argument(command, options.scene);
  add_solver_options(command, options.solver);
  add_camera_options(command, options.camera);
  add_view_independent_option(command, options.view_independent);
  viewer_options& window = options.window;
  CLI::Option* frames = command.add_option("--frames", window.frames, "scripted run: draw this many frames")
                            ->check(CLI::Range(1, 1 << 30));
  command
      .add_option("--screenshot", window.screenshot_path,
                  "with --frames: after the scripted frames, save the window as PNG")
      ->needs(frames);
  command
      .add_option(
          "--still", window.still_path,
          "with --frames: ray trace a still at --size halfway through (as the panel's button does), save it as PNG")
      ->needs(frames);
  command.add_flag("--error-plot", window.error_plot,
                   "path trace a 64x64 reference of the camera at the start and plot the error against it");
  command.add_flag("--exit", window.exit_after, "with --frames: quit after the scripted frames")->needs(frames);
  CLI::Option* screenshots = command
                                 .add_option("--screenshots", window.screenshots_dir,
                                             "with --frames: save the view (without the panel) at frame 1 and every "
                                             "--screenshot-every frames into DIR")
                                 ->check(CLI::ExistingDirectory)
                                 ->needs(frames);
  command.add_option("--screenshot-every", window.screenshot_every, "with --screenshots: frames between screenshots")
      ->check(CLI::Range(1, 1 << 30))
      ->needs(screenshots);
  command
      .add_option("--refined-passes", window.refined_passes,
                  "with --frames: the last frame waits until refinement at rest shows this many passes")
      ->check(CLI::Range(1, 64))
      ->needs(frames);
  command
      .add_flag("--no-panel-in-screenshot{false}", window.screenshot_panel,
                "with --screenshot: save the view without the panel")
      ->needs(frames);
  command.add_flag("--no-refine-at-rest{false}", window.refine_at_rest,
                   "keep the live Gouraud view while the camera rests (the panel's \"refine at rest\" off)");
  command.add_flag("--paused", window.start_paused, "mesh and show the scene but start the solver paused");
  command
      .add_option("--exposure", window.exposure,
                  "a fixed exposure (displayed value = radiance x exposure); default: automatic, from the picture")
      ->check(number_in(min_exposure, max_exposure));
  command.add_option("--msaa", window.msaa, "window antialiasing samples (default: 4 on a GPU, 0 on software GL)")
      ->check(CLI::Range(0, 16));
}

std::string check_view_options(const CLI::App& command, view_options& options) {
  if (std::string e = check_solver_options(command, options.solver); !e.empty()) return e;
  if (std::string e = check_view_independent_option(command, options.solver); !e.empty()) return e;
  return check_output_files(
      {{"--screenshot", options.window.screenshot_path, false}, {"--still", options.window.still_path, false}});
}

int run_view(const view_options& options) {
  scene s;
  viewer_options window = options.window;
  if (int code = load_for_command(options.scene, &options.camera, s, &window.load_warnings,
                                  {{"--screenshot", window.screenshot_path}, {"--still", window.still_path}});
      code != exit_ok)
    return code;
  solver_settings solver = options.solver;
  // The scene camera leads the first steps; the window re-targets at its
  // own camera whenever it rests (hierarchical only).
  if (!options.view_independent && solver.method == solver_method::hierarchical) solver.view = s.view;
  return run_viewer(s, solver, window);
}

}  // namespace bounce
