// Writing the patch mesh with its radiosity as PLY (ASCII), which MeshLab
// and Blender open.
#pragma once

#include <ostream>
#include <vector>

#include "mesh/patch_mesh.h"

namespace bounce {

// Vertices keep the scene's coordinates and carry float properties
// radiosity_r/g/b (B, unscaled) and tone-mapped sRGB colours red/green/blue
// (radiance B/pi x `exposure`). Faces are the elements. Bakes go through
// radiosity/bake.h, which chooses the exposure and writes the file whole.
void write_ply(std::ostream& out, const patch_mesh& mesh, const std::vector<rgb>& radiosity, double exposure);

}  // namespace bounce
