// Camera files: the scene format's camera object on its own, as the window
// saves views and bookmarks and as `--camera FILE` reads them back:
// {"camera": {"eye": ..., "target": ..., "up": ..., "fov": ..., "size":
// [w, h]}}. What camera_json writes, parse_camera_text reads back exactly.
#pragma once

#include <string>

#include "scene/scene.h"

namespace bounce {

// Reads a camera file (disk or "embedded:") into `cam`; keys left out keep
// `cam`'s values, and on failure `cam` is untouched. Errors name the file
// (`where` for text already read) and the key.
bool load_camera_file(const std::string& path, camera& cam, std::string& error);
bool parse_camera_text(const std::string& text, const std::string& where, camera& cam, std::string& error);

// `cam` as a camera file (every key written; numbers round-trip exactly).
std::string camera_json(const camera& cam);

}  // namespace bounce
