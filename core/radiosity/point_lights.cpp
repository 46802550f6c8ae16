#include "radiosity/point_lights.h"

#include <algorithm>
#include <atomic>

#include "base/parallel.h"

namespace bounce {

rgb point_light_irradiance(const scene& s, const form_factor_context& context, const vec3& p, const vec3& n,
                           std::uint64_t& rays) {
  rgb irradiance(0.0);
  for (const point_light& light : s.lights) {
    const vec3 to_light = light.position - p;
    const double r2 = glm::dot(to_light, to_light);
    const double cosine = glm::dot(n, to_light) / std::sqrt(r2);
    if (!(cosine > 0.0)) continue;
    ++rays;
    if (!visible(context, p, n, light.position, vec3(0.0))) continue;
    irradiance += light.intensity * (cosine / r2);  // I cos / r^2
  }
  return irradiance;
}

std::vector<rgb> point_light_radiosity(const scene& s, const patch_mesh& mesh, const form_factor_context& context,
                                       std::uint64_t& rays, std::size_t first) {
  std::vector<rgb> out(mesh.vertex_count(), rgb(0.0));
  std::atomic<std::uint64_t> cast{0};
  auto light_vertices = [&](std::size_t begin, std::size_t end) {
    std::uint64_t local = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t v = first + i;
      out[v] = mesh.vertex_rho[v] * point_light_irradiance(s, context, mesh.receive_points[v], mesh.normals[v], local);
    }
    cast += local;
  };
  for_each_block(context.params.parallel, mesh.vertex_count() - std::min(first, mesh.vertex_count()), 256,
                 light_vertices);
  rays += cast;
  return out;
}

}  // namespace bounce
