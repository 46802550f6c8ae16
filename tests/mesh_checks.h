// Checks on meshes that several tests make: smooth pieces, T-vertices,
// area per surface.
#pragma once

#include <map>
#include <vector>

#include "mesh/patch_mesh.h"

namespace bounce::test_support {

// Connected pieces of the mesh (vertices linked by elements): a smooth
// piece of a surface. Creases and material changes split vertices, so the
// faces of a box are pieces of their own.
inline std::vector<int> pieces(const patch_mesh& mesh) {
  std::vector<int> parent(mesh.vertex_count());
  for (std::size_t v = 0; v < parent.size(); ++v) parent[v] = int(v);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const glm::ivec3& t : mesh.elements) {
    parent[find(t[1])] = find(t[0]);
    parent[find(t[2])] = find(t[0]);
  }
  for (std::size_t v = 0; v < parent.size(); ++v) parent[v] = find(int(v));
  return parent;
}

// Vertices lying strictly inside another element's edge of the same smooth
// piece: T-vertices, the cracks of a non-conforming mesh.
inline std::size_t hanging_vertices(const patch_mesh& mesh) {
  const std::vector<int> piece = pieces(mesh);
  std::map<int, std::vector<int>> by_piece;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) by_piece[piece[v]].push_back(int(v));
  std::size_t hanging = 0;
  const double tolerance = 1e-9 * mesh.scene_diagonal;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    for (int k = 0; k < 3; ++k) {
      const vec3 a = mesh.positions[t[k]], b = mesh.positions[t[(k + 1) % 3]];
      const double length2 = glm::dot(b - a, b - a);
      for (int v : by_piece[piece[t[0]]]) {
        if (v == t[0] || v == t[1] || v == t[2]) continue;
        const vec3 p = mesh.positions[v];
        const double s = glm::dot(p - a, b - a) / length2;
        if (s <= 1e-9 || s >= 1.0 - 1e-9) continue;
        if (glm::length(p - (a + (b - a) * s)) < tolerance) ++hanging;
      }
    }
  }
  return hanging;
}

inline std::map<int, double> area_by_surface(const patch_mesh& mesh) {
  std::map<int, double> area;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) area[mesh.element_surfaces[e]] += mesh.element_areas[e];
  return area;
}

}  // namespace bounce::test_support
