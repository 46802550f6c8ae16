// `bounce info`: load and validate a scene, print its counts (text or JSON).
#pragma once

#include <string>

namespace bounce {

// `max_edge` 0: the scene's default tessellation size for curved surfaces.
int run_info(const std::string& path, bool as_json, double max_edge);

}  // namespace bounce
