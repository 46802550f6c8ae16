// Strict Wavefront OBJ/MTL reader: every problem is reported with its file
// and line (tinyobjloader turns malformed numbers into zeros silently, which
// is why Bounce reads these two small formats itself).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace bounce {

// Thrown by the readers; the message already names file and line or object.
// `warnings` holds what the reader had to say before it failed, so that the
// caller can print them before the error.
struct load_error : std::runtime_error {
  using std::runtime_error::runtime_error;
  std::vector<std::string> warnings;
};

// Limits on what an OBJ or MTL file may say (see docs/scene-format.md).
// Every number must be finite and at most this in magnitude: no real scene
// has coordinates, colours or exponents near it, and it keeps areas, powers
// (pi * Ke * area) and the fitted camera far from overflow.
inline constexpr double max_file_number = 1e9;
// Faces with more corners are refused: ear clipping costs O(n r) for r
// reflex corners, about 0.3 s at this size in the worst case measured.
inline constexpr std::size_t max_face_corners = 10'000;
// Reflectances of 1 or more (Kd 1 1 1, vertex colours of 1) become this,
// as Valve's VRAD does; rho + kr + kt over 1 is scaled down to it.
inline constexpr double max_reflectance = 0.99;

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

// The same for an image already in memory (one inside a glTF file); `what`
// names it in the message ("image 2").
texture decode_image_texture(std::string_view bytes, const std::string& name, const std::string& where,
                             const std::string& what);

// Numbers in the model readers' messages: %g, and a grey colour as one number.
std::string format_value(double v);
std::string format_value(const rgb& c);

}  // namespace bounce
