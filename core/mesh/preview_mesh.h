// The scene's surfaces as they come, before the mesher has made its
// patch mesh: every surface tessellated (curved ones at the default
// element size, polygons as given) with nothing cut, welded or refined.
// The window draws it, lit by a headlight, while the real mesh is built
// (seconds at a million triangles), so a big scene shows its shape at once.
// Not for solving: no patches beyond one per element, no receive points
// off the surface, vertices shared only within a tessellation.
#pragma once

#include "mesh/patch_mesh.h"

namespace bounce {

patch_mesh make_preview_mesh(const scene& s);

}  // namespace bounce
