#include "scene/camera_file.h"

#include <optional>

#include "scene/json_scene.h"
#include "scene/reader_support.h"
#include "scene/scene_validate.h"

namespace bounce {
namespace {

using json = nlohmann::json;

}  // namespace

bool parse_camera_text(const std::string& text, const std::string& where, camera& cam, std::string& error) {
  try {
    const json doc = parse_json(where, text);
    const json_reader r{where};
    r.only_keys(doc, "camera file", {"camera"});
    if (!doc.contains("camera")) r.fail("camera file", "needs a 'camera' object");
    camera c = cam;
    read_camera(r, doc["camera"], c, /*partial=*/true);
    // The camera it makes, checked here, so that a fault is the file's.
    if (std::string e = check_camera(c); !e.empty()) r.fail("camera file", e.substr(e.find(": ") + 2));
    cam = c;
    return true;
  } catch (const load_error& e) {
    error = e.what();
    return false;
  }
}

bool load_camera_file(const std::string& path, camera& cam, std::string& error) {
  const std::optional<std::string> text = read_file(path);
  if (!text) {
    error = path + ": cannot read file";
    return false;
  }
  return parse_camera_text(*text, path, cam, error);
}

std::string camera_json(const camera& cam) {
  const json doc = {{"camera",
                     {{"eye", {cam.eye.x, cam.eye.y, cam.eye.z}},
                      {"target", {cam.target.x, cam.target.y, cam.target.z}},
                      {"up", {cam.up.x, cam.up.y, cam.up.z}},
                      {"fov", cam.fov_y_degrees},
                      {"size", {cam.width, cam.height}}}}};
  return doc.dump(2) + "\n";
}

}  // namespace bounce
