#include "scene/scene_info.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "scene/tessellate.h"

namespace bounce {

double default_max_edge(const scene& s) {
  bounds3 b = scene_bounds(s);
  double diagonal = glm::length(b.max - b.min);
  return diagonal > 0.0 ? diagonal / 24.0 : 1.0;
}

double hierarchical_max_edge(const scene& s) {
  return default_max_edge(s) * 24.0 / 10.0;
}

std::string summarize_scene(const scene& s, double max_edge, scene_summary& out) {
  out = {};
  out.max_edge = max_edge;
  out.surfaces = s.surfaces.size();
  out.materials = s.materials.size();
  out.textures = s.textures.size();
  for (const punctual_light& l : s.lights)
    ++(l.type == light_type::spot ? out.spot_lights : l.type == light_type::sun ? out.suns : out.point_lights);
  out.sky = s.sky.on();
  out.bounds = scene_bounds(s);

  auto emits = [&](int m) { return any_positive(s.materials[m].ke); };
  std::set<int> emitting;
  double estimate = 0.0;  // in double: a tiny max edge overflows any integer
  for (const surface& surf : s.surfaces) {
    estimate += double(estimate_triangles(surf, max_edge));
    bool surface_emits = false;
    std::visit(
        [&](const auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, polygon_mesh>) {
            ++out.polygon_meshes;
            out.polygons += g.faces.size();
            for (const polygon_face& f : g.faces)
              if (emits(f.material)) {
                emitting.insert(f.material);
                surface_emits = true;
              }
          } else {
            if constexpr (std::is_same_v<T, sphere>) ++out.spheres;
            if constexpr (std::is_same_v<T, quadric>) ++out.quadrics;
            if constexpr (std::is_same_v<T, bezier_surface>) {
              ++out.bezier_surfaces;
              out.patches += g.patches.size();
            }
            if constexpr (std::is_same_v<T, bspline_surface>) {
              ++out.bspline_surfaces;
              out.patches += static_cast<std::size_t>(g.rows - 3) * (g.cols - 3);
            }
            if (emits(g.material)) {
              emitting.insert(g.material);
              surface_emits = true;
            }
          }
        },
        surf.geometry);
    out.emitting_surfaces += surface_emits ? 1 : 0;
  }
  out.emitting_materials = emitting.size();
  if (estimate > double(max_tessellated_triangles)) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "tessellating at max edge %g would make %s %.3g triangles (limit %zu); use a larger --max-edge",
                  max_edge, std::isfinite(estimate) ? "about" : "more than", std::min(estimate, 1e308),
                  std::size_t(max_tessellated_triangles));
    return text;
  }
  for (const surface& surf : s.surfaces) out.triangles += tessellate(surf, max_edge).triangles.size();
  return {};
}

}  // namespace bounce
