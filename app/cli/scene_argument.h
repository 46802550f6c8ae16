// The scene a command works on: its SCENE argument, and the loading of
// that scene with the warnings printed and the camera overrides applied.
#pragma once

#include <string>
#include <vector>

#include "cli/camera_options.h"
#include "cli/option_values.h"
#include "scene/scene.h"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace bounce {

// SCENE given but empty (`bounce render ""`, an unset variable) is refused:
// it would otherwise mean the built-in Cornell box.
CLI::Validator named_scene();

// SCENE, with the help every command shows for it.
void add_scene_argument(CLI::App& command, std::string& path);

// Loads the scene named on a command line (empty: the embedded Cornell box)
// and applies the camera overrides (null: none); prints the warnings
// (grouped: warning_groups.h), then any error, and returns its exit code
// (exit_ok when loaded). `warnings`, when given, receives them one by one.
// `outputs` are the files the command will write: one that would
// overwrite a file the scene was read from is refused (exit 2) before any
// work.
int load_for_command(const std::string& path, const camera_options* camera_overrides, scene& s,
                     std::vector<std::string>* warnings = nullptr, const std::vector<output_file>& outputs = {});

// Whether what a command itself will allocate (a picture, a photon map)
// fits in the memory left (memory_room.h). If not, prints "error: SCENE:
// `what` needs at least BYTES, more than the ROOM available (BOUND);
// `advice`" and returns false.
bool fits_in_memory(const scene& s, double bytes, const std::string& what, const std::string& advice);

}  // namespace bounce
