#include "render/closed_surface.h"

#include <cstdint>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace bounce::gl {

bool bounds_solid_outward(const std::vector<unsigned int>& indices, std::size_t first, std::size_t count,
                          const std::vector<glm::vec3>& positions) {
  if (positions.empty() || count < 12 || count % 3 != 0 || first + count > indices.size())
    return false;  // a tetrahedron at least
  // Directed edge a -> b, keyed a << 32 | b: +1 for itself, and its reverse
  // must cancel it exactly.
  std::unordered_map<std::uint64_t, int> edges;
  edges.reserve(count);
  double volume = 0.0;  // six times the signed volume, about a corner (no cancellation far from the origin)
  const glm::dvec3 origin(positions[indices[first] < positions.size() ? indices[first] : 0]);
  for (std::size_t t = first; t < first + count; t += 3) {
    const unsigned int v[3] = {indices[t], indices[t + 1], indices[t + 2]};
    for (const unsigned int i : v)
      if (i >= positions.size()) return false;
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = v[k], b = v[(k + 1) % 3];
      if (a == b) return false;
      if (++edges[a << 32 | b] != 1) return false;  // an edge used twice the same way
    }
    const glm::dvec3 p0 = glm::dvec3(positions[v[0]]) - origin, p1 = glm::dvec3(positions[v[1]]) - origin,
                     p2 = glm::dvec3(positions[v[2]]) - origin;
    volume += glm::dot(p0, glm::cross(p1, p2));
  }
  for (const auto& [edge, uses] : edges)
    if (!edges.count(edge >> 32 | (edge & 0xffffffffu) << 32)) return false;  // an open edge
  return volume > 0.0;
}

}  // namespace bounce::gl
