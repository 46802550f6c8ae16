#include "scene/two_sided.h"

#include <algorithm>

namespace bounce {

bool turned_over(const shape& in, shape& out) {
  return std::visit(
      [&](const auto& g) -> bool {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, polygon_mesh>) {
          polygon_mesh m = g;
          for (vec3& n : m.normals) n = -n;
          for (polygon_face& f : m.faces) {
            std::reverse(f.position.begin(), f.position.end());
            std::reverse(f.normal.begin(), f.normal.end());
            std::reverse(f.uv.begin(), f.uv.end());
          }
          out = std::move(m);
          return true;
        } else if constexpr (std::is_same_v<T, quadric>) {
          // The normal is the gradient's direction: negate the polynomial.
          quadric q = g;
          for (double* c : {&q.a, &q.b, &q.c, &q.d, &q.e, &q.f, &q.g, &q.h, &q.j, &q.k}) *c = -*c;
          out = q;
          return true;
        } else if constexpr (std::is_same_v<T, bezier_surface>) {
          // Normal = dP/du x dP/dv: swapping u and v (transposing each 4 x 4 patch) turns it over.
          bezier_surface b = g;
          for (auto& patch : b.patches)
            for (int r = 0; r < 4; ++r)
              for (int c = r + 1; c < 4; ++c) std::swap(patch[r * 4 + c], patch[c * 4 + r]);
          out = std::move(b);
          return true;
        } else if constexpr (std::is_same_v<T, bspline_surface>) {
          bspline_surface b = g;
          b.rows = g.cols;
          b.cols = g.rows;
          for (int r = 0; r < g.rows; ++r)
            for (int c = 0; c < g.cols; ++c)
              b.control[std::size_t(c) * g.rows + r] = g.control[std::size_t(r) * g.cols + c];
          out = std::move(b);
          return true;
        } else {
          return false;
        }
      },
      in);
}

std::vector<std::string> add_back_sides(scene& s) {
  std::vector<std::string> warnings;
  auto two_sided = [&](int material) {
    return material >= 0 && material < int(s.materials.size()) && s.materials[std::size_t(material)].two_sided;
  };
  const std::size_t count = s.surfaces.size();
  for (std::size_t i = 0; i < count; ++i) {
    if (s.surfaces[i].back_side >= 0 || s.surfaces[i].back_of >= 0) continue;
    shape front = s.surfaces[i].geometry;
    bool any = false;
    if (auto* mesh = std::get_if<polygon_mesh>(&front)) {
      // Only the faces with a two-sided material get a back.
      std::erase_if(mesh->faces, [&](const polygon_face& f) { return !two_sided(f.material); });
      any = !mesh->faces.empty();
    } else {
      std::visit(
          [&](const auto& g) {
            if constexpr (!std::is_same_v<std::decay_t<decltype(g)>, polygon_mesh>) any = two_sided(g.material);
          },
          front);
    }
    if (!any) continue;
    surface back;
    if (!turned_over(front, back.geometry)) {
      warnings.push_back(s.surfaces[i].name + ": two_sided has no effect on a sphere (its inside is one-sided)");
      continue;
    }
    back.name = s.surfaces[i].name + " (back)";
    back.source = s.surfaces[i].source;
    back.back_of = int(i);
    s.surfaces[i].back_side = int(s.surfaces.size());
    s.surfaces.push_back(std::move(back));
  }
  return warnings;
}

}  // namespace bounce
