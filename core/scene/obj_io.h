// Strict Wavefront OBJ/MTL reader: every problem is reported with its file
// and line (tinyobjloader turns malformed numbers into zeros silently, which
// is why Bounce reads these two small formats itself).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "scene/reader_support.h"  // load_error
#include "scene/scene.h"

namespace bounce {

struct obj_read_result {
  std::vector<surface> surfaces;  // one polygon mesh per `o` object
  std::vector<std::string> warnings;
  std::size_t dropped_faces = 0;
};

// Reads `path` (disk or "embedded:"), its MTL libraries and their textures.
// New materials and textures are appended to the scene's lists and faces
// refer to them by index. Throws load_error.
obj_read_result read_obj(const std::string& path, std::vector<material>& materials, std::vector<texture>& textures);

}  // namespace bounce
