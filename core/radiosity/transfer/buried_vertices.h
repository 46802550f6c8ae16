// Vertices inside solids. Where one surface passes through another (the
// teapot's spout and handle through its body, a knob into its lid, a
// chair leg through a floor) the vertices inside receive no light, and the
// elements that straddle the crossing fade from lit to black across their
// visible part: dark wedges and stripes in the view. Such a vertex is
// found by rays: every ray it sends over its hemisphere meets the back of
// a surface first. Its published value is then taken from the vertices
// beside it that are outside; the solve itself is unchanged.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <span>
#include <vector>

#include "mesh/patch_mesh.h"
#include "radiosity/transfer/occlusion.h"

namespace bounce {

// Rays each vertex sends: along its normal, and the rest 50 degrees off it.
inline constexpr int buried_probe_rays = 6;

// Extends buried (one flag per vertex of `mesh`) to every vertex of `mesh`,
// keeping the flags it has: vertices keep their indices when a mesh is
// refined, so only new vertices cast rays. `occluders` is the mesh that
// `scene` was built from (its elements' normals tell front from back);
// `offset` lifts the rays off their surface.
void find_buried_vertices(const patch_mesh& mesh, const patch_mesh& occluders, const occlusion_scene& scene,
                          double offset, std::vector<bool>& buried);

// Replaces the value of each buried vertex, in every array of `arrays`
// (one value per vertex each), by the area-weighted mean of its element
// neighbours that are outside (or were filled in an earlier round, for
// vertices deeper in). A buried vertex with no such neighbour within 16
// rounds keeps its value. Only the elements that touch a buried vertex
// are visited.
void fill_buried_vertices(const patch_mesh& mesh, const std::vector<bool>& buried,
                          std::initializer_list<std::span<rgb>> arrays);

}  // namespace bounce
