// Whether a set of triangles bounds a solid with its faces wound
// counter-clockwise seen from outside. From any eye outside such a solid
// its back faces are hidden by its front faces, so the renderer may cull
// them: llvmpipe shades on the CPU, and a mirror or glass sphere drawn
// without culling shades its far half for nothing. Plain CPU work.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

namespace bounce::gl {

// `indices[first .. first + count)` are triangles into `positions`. True
// when every directed edge is met once and its reverse once (closed, a
// manifold, wound one way throughout) and the enclosed volume is positive
// (counter-clockwise from outside). Vertices are taken by index: a surface
// whose vertices are split along seams counts as open (never culled).
bool bounds_solid_outward(const std::vector<unsigned int>& indices, std::size_t first, std::size_t count,
                          const std::vector<glm::vec3>& positions);

}  // namespace bounce::gl
