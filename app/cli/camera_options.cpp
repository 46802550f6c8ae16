#include "cli/camera_options.h"

#include <CLI/CLI.hpp>

#include "cli/option_values.h"
#include "scene/scene_validate.h"

namespace bounce {

void add_camera_options(CLI::App& command, camera_options& o) {
  command.add_option("--camera", o.file,
                     "camera file ({\"camera\": {...}} as in a scene file, e.g. saved from the window's panel); "
                     "--eye, --target, --up, --fov and --size override it");
  command.add_option("--eye", o.eye, "camera position x,y,z")->check(vec3_value());
  command.add_option("--target", o.target, "point looked at x,y,z")->check(vec3_value());
  command.add_option("--up", o.up, "up direction x,y,z")->check(vec3_value());
  command.add_option("--fov", o.fov, "vertical field of view, degrees")
      ->check(number_in(min_fov_degrees, max_fov_degrees));
  command
      .add_option("--size", o.size,
                  "image size WxH (1 to " + std::to_string(max_image_side) + " per side, at most " +
                      std::to_string(max_image_pixels) + " pixels)")
      ->check(image_size_value());
}

std::string apply_camera_options(const camera_options& options, camera& view) {
  camera c = view;
  const std::pair<const char*, const std::string*> vectors[] = {
      {"--eye", &options.eye}, {"--target", &options.target}, {"--up", &options.up}};
  vec3* fields[] = {&c.eye, &c.target, &c.up};
  for (int i = 0; i < 3; ++i) {
    if (vectors[i].second->empty()) continue;
    auto v = parse_vec3(*vectors[i].second);
    if (!v) return std::string(vectors[i].first) + ": expected x,y,z (three numbers), got '" + *vectors[i].second + "'";
    *fields[i] = *v;
  }
  if (options.fov) {
    if (!(*options.fov >= min_fov_degrees && *options.fov <= max_fov_degrees))
      return "--fov: must be from 0.001 to 179 degrees";
    c.fov_y_degrees = *options.fov;
  }
  if (!options.size.empty()) {
    auto size = parse_size(options.size);
    if (!size) return "--size: expected WxH, got '" + options.size + "'";
    c.width = size->first;
    c.height = size->second;
  }
  // The same rules as a scene file's camera.
  scene probe;
  probe.view = c;
  probe.lights.push_back({vec3(0.0), rgb(1.0)});
  probe.materials.push_back({});
  probe.surfaces.push_back({"probe", "", sphere{}});
  if (std::string e = validate_scene(probe); !e.empty()) return "camera override: " + e;
  view = c;
  return {};
}

}  // namespace bounce
