// The camera overrides of every command that renders (view, render,
// trace): a camera file, then --eye, --target, --up, --fov and --size over
// it, checked by the same rules as a scene file's camera.
#pragma once

#include <optional>
#include <string>

#include "scene/scene.h"

namespace CLI {
class App;
}  // namespace CLI

namespace bounce {

// The overrides as typed.
struct camera_options {
  std::string file;  // --camera: a camera file, loaded before the other overrides apply
  std::string eye, target, up, size;
  std::optional<double> fov;
};

void add_camera_options(CLI::App& command, camera_options& options);

// Applies the overrides (not the file) to `view`; returns an error message
// naming the option at fault, or an empty string (then `view` is changed).
std::string apply_camera_options(const camera_options& options, camera& view);

}  // namespace bounce
