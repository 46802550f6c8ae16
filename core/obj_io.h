// Strict Wavefront OBJ/MTL reader: every problem is reported with its file
// and line (tinyobjloader turns malformed numbers into zeros silently, which
// is why Bounce reads these two small formats itself).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "scene.h"

namespace bounce {

// Thrown by the readers; the message already names file and line or object.
struct load_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct obj_read_result {
  std::vector<surface> surfaces;  // one polygon mesh per `o` object
  std::vector<std::string> warnings;
  std::size_t dropped_faces = 0;
};

// Reads `path` (disk or "embedded:"), its MTL libraries and their textures.
// New materials and textures are appended to the scene's lists and faces
// refer to them by index. Throws load_error.
obj_read_result read_obj(const std::string& path, std::vector<material>& materials, std::vector<texture>& textures);

// Reads an image texture (PNG, JPEG, ... via stb_image) into linear RGB.
// Throws load_error naming `where` (the file and line that asked for it).
texture read_image_texture(const std::string& path, const std::string& name, const std::string& where);

}  // namespace bounce
