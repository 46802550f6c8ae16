#include "mesh/preview_mesh.h"

#include <algorithm>
#include <numbers>
#include <vector>

#include "scene/framing.h"
#include "scene/scene_info.h"
#include "scene/tessellate.h"

namespace bounce {

patch_mesh make_preview_mesh(const scene& s) {
  patch_mesh out;
  const double max_edge = default_max_edge(s);
  for (std::size_t i = 0; i < s.surfaces.size(); ++i) {
    const triangle_mesh t = tessellate(s.surfaces[i], max_edge);
    const int first = int(out.positions.size());
    // A vertex takes the material of the first triangle that uses it.
    std::vector<int> material(t.positions.size(), -1);
    for (std::size_t k = 0; k < t.triangles.size(); ++k)
      for (int c = 0; c < 3; ++c)
        if (material[std::size_t(t.triangles[k][c])] < 0) material[std::size_t(t.triangles[k][c])] = t.materials[k];
    for (std::size_t v = 0; v < t.positions.size(); ++v) {
      const int m = material[v];
      const bool known = m >= 0 && std::size_t(m) < s.materials.size();
      out.positions.push_back(t.positions[v]);
      out.normals.push_back(t.normals[v]);
      out.receive_points.push_back(t.positions[v]);
      out.vertex_rho.push_back(known ? s.materials[std::size_t(m)].rho : rgb(0.5));
      out.vertex_emission.push_back(known ? std::numbers::pi * s.materials[std::size_t(m)].ke : rgb(0.0));
      out.vertex_surfaces.push_back(int(i));
      out.uvs.push_back(t.uvs[v]);
    }
    for (std::size_t k = 0; k < t.triangles.size(); ++k) {
      const glm::ivec3 tri = t.triangles[k] + glm::ivec3(first);
      const vec3 a = out.positions[std::size_t(tri[0])], b = out.positions[std::size_t(tri[1])],
                 c = out.positions[std::size_t(tri[2])];
      const vec3 cross = glm::cross(b - a, c - a);
      const double length = glm::length(cross);
      if (!(length > 0.0)) continue;
      out.elements.push_back(tri);
      out.element_normals.push_back(cross / length);
      out.element_areas.push_back(0.5 * length);
      out.element_surfaces.push_back(int(i));
      out.element_materials.push_back(t.materials[k]);
      out.element_patches.push_back(int(out.patch_areas.size()));
      out.patch_corners.push_back({a, b, c});
      out.patch_normals.push_back(cross / length);
      out.patch_areas.push_back(0.5 * length);
    }
  }
  const bounds3 b = scene_bounds(s);
  out.scene_diagonal = std::max(glm::length(b.max - b.min), 1e-300);
  out.max_edge = max_edge;
  return out;
}

}  // namespace bounce
