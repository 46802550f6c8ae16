// Writing the patch mesh with its radiosity as PLY (ASCII), which MeshLab
// and Blender open.
#pragma once

#include <string>
#include <vector>

#include "mesh/patch_mesh.h"

namespace bounce {

// Vertices keep the scene's coordinates and carry float properties
// radiosity_r/g/b (B, unscaled) and tone-mapped sRGB colours red/green/blue
// (radiance B/pi x `exposure`). Faces are the elements. Returns false
// with `error` naming the file when it cannot be written. Bakes go through
// radiosity/bake.h, which chooses the exposure and writes whole.
bool write_ply(const std::string& path, const patch_mesh& mesh, const std::vector<rgb>& radiosity, double exposure,
               std::string& error);

}  // namespace bounce
