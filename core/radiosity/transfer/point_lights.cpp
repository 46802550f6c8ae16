#include "radiosity/transfer/point_lights.h"

#include <algorithm>
#include <atomic>
#include <functional>
#include <numbers>

#include "base/parallel.h"
#include "scene/lights.h"
#include "scene/sky.h"

namespace bounce {

namespace {

// Stratified, cosine-weighted shadow rays to the sky: pi times their mean
// radiance is the irradiance, so an unoccluded uniform sky gives pi L exactly.
constexpr int sky_rays = 64;

rgb sky_irradiance(const scene& s, const form_factor_context& context, const vec3& p, const vec3& n,
                   std::uint64_t& rays) {
  // Beyond the scene's bounds from any point inside them.
  const double far = 4.0 * std::max(context.mesh->scene_diagonal, 1e-12);
  const std::uint64_t seed =
      std::hash<double>()(p.x) ^ (std::hash<double>()(p.y) << 1) ^ (std::hash<double>()(p.z) << 2);
  rgb sum(0.0);
  for (int k = 0; k < sky_rays; ++k) {
    const vec3 dir = stratified_cosine_direction(n, k, sky_rays, seed);
    if (visible(context, p, n, p + far * dir, vec3(0.0))) sum += sky_radiance(s.sky, dir);
  }
  rays += sky_rays;
  return sum * (std::numbers::pi / sky_rays);
}

}  // namespace

rgb point_light_irradiance(const scene& s, const form_factor_context& context, const vec3& p, const vec3& n,
                           std::uint64_t& rays) {
  const rgb sky = s.sky.on() ? sky_irradiance(s, context, p, n, rays) : rgb(0.0);
  return sky + punctual_light_irradiance(s, context, p, n, rays);
}

rgb punctual_light_irradiance(const scene& s, const form_factor_context& context, const vec3& p, const vec3& n,
                              std::uint64_t& rays) {
  rgb irradiance(0.0);
  const double far = 4.0 * std::max(context.mesh->scene_diagonal, 1e-12);
  for (const punctual_light& light : s.lights) {
    const light_arrival a = light_at(light, p, far);
    const double cosine = glm::dot(n, a.to_light);
    if (!(cosine > 0.0) || !any_positive(a.irradiance)) continue;
    ++rays;
    if (!visible(context, p, n, a.shadow_end, vec3(0.0))) continue;
    irradiance += a.irradiance * cosine;  // I share cos / r^2, or E cos for a sun
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
