#include "cli/scene_argument.h"

#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "base/memory_room.h"
#include "cli/option_values.h"
#include "common/exit_code.h"
#include "scene/camera_file.h"
#include "scene/scene_io.h"
#include "scene/warning_groups.h"

namespace bounce {
namespace {

// Grouped by what they say: a model with thousands of degenerate faces
// gets one line with the count.
void print_warnings(const load_report& report) {
  for (const warning_group& g : group_warnings(report.warnings)) std::cerr << "warning: " << describe(g) << "\n";
}

}  // namespace

CLI::Validator named_scene() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "is empty (an unset shell variable?): name a scene file, or leave SCENE out for the "
                              "built-in Cornell box"
                            : "";
      },
      "");
}

void add_scene_argument(CLI::App& command, std::string& path) {
  command
      .add_option("SCENE", path,
                  "scene file (.json, .obj, .gltf, .glb, .ply, .stl, .dae, .fbx, .3ds, .off), or generated:NAME (e.g. "
                  "generated:interior-1m)")
      ->check(named_scene());
}

// Loads the scene named on the command line (or the embedded default) and
// applies the camera overrides. Prints the error and returns its exit code
// (exit_ok on success): a scene that cannot be used is an input error, an
// override that makes the camera invalid a usage error.
int load_for_command(const std::string& path, const camera_options* camera_overrides, scene& s,
                     std::vector<std::string>* warnings, const std::vector<output_file>& outputs) {
  load_report report;
  if (!load_scene(path.empty() ? default_scene_path : path, s, report)) {
    print_warnings(report);  // what was said before the failure often explains it
    std::cerr << "error: " << report.error << "\n";
    return exit_input_error;
  }
  print_warnings(report);
  if (warnings) *warnings = report.warnings;
  if (std::string e = check_outputs_against_inputs(outputs, report.inputs); !e.empty()) {
    std::cerr << "error: " << e << "\n";
    return exit_usage;
  }
  if (camera_overrides) {
    // A camera file is a file that may be unusable (exit 1); the options
    // typed over it are the command line (exit 2).
    const camera scene_camera = s.view;
    if (std::string e; !camera_overrides->file.empty() && !load_camera_file(camera_overrides->file, s.view, e)) {
      std::cerr << "error: --camera: " << e << "\n";
      return exit_input_error;
    }
    // Whose size it is, for the message below: the camera file's, if it set one.
    const bool file_sized = s.view.width != scene_camera.width || s.view.height != scene_camera.height;
    if (std::string e = apply_camera_options(*camera_overrides, s.view); !e.empty()) {
      std::cerr << "error: " << e << "\n";
      return exit_usage;
    }
    // The scene file's or the camera file's size, when --size did not
    // replace it: the same limits.
    if (std::string e = check_image_size(s.view.width, s.view.height); !e.empty()) {
      std::cerr << "error: " << (file_sized ? camera_overrides->file : s.source) << ": camera.size: " << e
                << " (use --size)\n";
      return exit_input_error;
    }
  }
  return exit_ok;
}

bool fits_in_memory(const scene& s, double bytes, const std::string& what, const std::string& advice) {
  const memory_room room = available_memory();
  if (bytes <= room.bytes) return true;
  std::fprintf(stderr, "error: %s: %s needs at least %s, more than the %s available (%s); %s\n", s.source.c_str(),
               what.c_str(), format_bytes(bytes).c_str(), format_bytes(room.bytes).c_str(), room.bound.c_str(),
               advice.c_str());
  return false;
}

}  // namespace bounce
