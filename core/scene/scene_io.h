// Loading and validating scenes: JSON scene files, bare Wavefront OBJ/MTL,
// glTF models, the formats read through assimp, procedural scenes and the Cornell box embedded in the
// binary. The readers (json_scene, obj_io, gltf_io) turn a file into a
// scene; load_scene picks the reader, then drops degenerate faces, adds
// back sides, validates and warns, so every scene it returns is valid.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace bounce {

// Name of the embedded default scene (the Cornell box, same bytes as
// assets/cornell_box/). Paths starting with "embedded:" are read from the
// binary, so relative references inside it resolve there too.
inline constexpr const char* default_scene_path = "embedded:cornell_box/cornell_box.json";

struct load_report {
  std::string error;                  // set when loading failed: "file:line: what"
  std::vector<std::string> warnings;  // things dropped or ignored, one line each
  std::size_t dropped_faces = 0;      // degenerate faces removed
  std::vector<std::string> inputs;    // every file read (reader_support.h's input_log)
};

// Paths "generated:NAME" build a procedural scene (procedural.h) by name,
// e.g. "generated:interior-1m"; nothing is read from disk.
inline constexpr std::string_view generated_prefix = "generated:";

// Loads a .json scene, a bare .obj, a glTF 2.0 .gltf/.glb or a PLY, STL,
// Collada, FBX, 3DS or OFF model (assimp_io.h; models get a camera fitted
// to the geometry) or a procedural scene ("generated:NAME") and validates it. On failure returns false, fills
// report.error with a message naming the file and the line or object, and leaves `out` untouched.
bool load_scene(const std::string& path, scene& out, load_report& report);

}  // namespace bounce
