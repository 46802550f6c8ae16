#include "point_lights.h"

#include <atomic>

#include "parallel.h"

namespace bounce {

std::vector<rgb> point_light_radiosity(const scene& s, const patch_mesh& mesh, const form_factor_context& context,
                                       std::uint64_t& rays) {
  std::vector<rgb> out(mesh.vertex_count(), rgb(0.0));
  std::atomic<std::uint64_t> cast{0};
  auto light_vertices = [&](std::size_t begin, std::size_t end) {
    std::uint64_t local = 0;
    for (std::size_t v = begin; v < end; ++v) {
      const vec3& p = mesh.receive_points[v];
      const vec3& n = mesh.normals[v];
      for (const point_light& light : s.lights) {
        const vec3 to_light = light.position - p;
        const double r2 = glm::dot(to_light, to_light);
        const double cosine = glm::dot(n, to_light) / std::sqrt(r2);
        if (!(cosine > 0.0)) continue;
        ++local;
        if (!visible(context, p, n, light.position, vec3(0.0))) continue;
        out[v] += mesh.vertex_rho[v] * light.intensity * (cosine / r2);  // irradiance I cos / r^2, reflected
      }
    }
    cast += local;
  };
  for_each_block(context.params.parallel, mesh.vertex_count(), 256, light_vertices);
  rays += cast;
  return out;
}

}  // namespace bounce
