#include "radiosity/transfer/specular_paths.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/parallel.h"
#include "base/random_stream.h"
#include "optics/specular_event.h"
#include "radiosity/transfer/mirror_images.h"
#include "radiosity/transfer/occlusion.h"
#include "scene/lights.h"

namespace bounce {
namespace {

using std::numbers::pi;

// Barycentric coordinates of a uniform point on a triangle (sqrt warp).
vec3 uniform_barycentric(double u1, double u2) {
  const double su = std::sqrt(u1);
  return {1.0 - su, su * (1.0 - u2), su * u2};
}

struct deposit {
  int element;
  vec3 weights;  // barycentric
  rgb power;
};

struct block_result {
  std::vector<deposit> deposits;
  specular_tally tally;
  std::uint64_t rays = 0;
};

class path_tracer {
 public:
  path_tracer(const scene& s, const form_factor_context& context) : s_(s), c_(context), mesh_(*context.mesh) {}

  // Follows a path that meets element e at barycentric b, going along d
  // (unit) with `power`; e is the specular element it was sent to (its
  // diffuse part has received from the source's form factors). A path
  // sent to a planar mirror (`planar_first`) deposits nothing until it
  // has left a specular surface that is not a planar mirror: before that,
  // it is light the mirror images carry.
  void follow(int e, vec3 b, vec3 d, rgb power, bool planar_first, random_stream& rng, block_result& out) const {
    specular_tally& tally = out.tally;
    const double far = 4.0 * std::max(mesh_.scene_diagonal, 1e-12);
    bool counts = !planar_first;
    for (int events = 0;; ++events) {
      const glm::ivec3 t = mesh_.elements[std::size_t(e)];
      const vec3 point = b[0] * mesh_.positions[t[0]] + b[1] * mesh_.positions[t[1]] + b[2] * mesh_.positions[t[2]];
      const vec3 face = mesh_.element_normals[std::size_t(e)];
      const bool front = glm::dot(d, face) < 0.0;
      const bool planar = c_.mirrors && c_.mirrors->element_mirror[std::size_t(e)];
      if (!counts && !planar && events > 0 && front) {
        const material& here = s_.materials[std::size_t(mesh_.element_materials[std::size_t(e)])];
        if (!any_positive(here.kr) && !any_positive(here.kt)) {  // diffuse, by planar mirrors alone
          tally.imaged += power;
          return;
        }
      }
      if (events > 0 && front && counts) {
        const rgb rho = (mesh_.vertex_rho[t[0]] + mesh_.vertex_rho[t[1]] + mesh_.vertex_rho[t[2]]) / 3.0;
        if (any_positive(rho)) {
          out.deposits.push_back({e, b, power});
          tally.deposited += power;
        }
      }
      if (!planar) counts = true;
      const material& m = s_.materials[std::size_t(mesh_.element_materials[std::size_t(e)])];
      vec3 normal = b[0] * mesh_.normals[t[0]] + b[1] * mesh_.normals[t[1]] + b[2] * mesh_.normals[t[2]];
      normal = glm::length(normal) > 0.0 ? glm::normalize(normal) : face;
      if (glm::dot(normal, face) < 0.0) normal = -normal;
      const vec3 n = front ? normal : -normal, n_face = front ? face : -face;  // facing the light
      const specular_event event = specular_split(m, d, n, front);
      double p_mirror = channel_mean(event.kr), p_transmit = event.refracted ? channel_mean(event.kt) : 0.0;
      const double sum = p_mirror + p_transmit;
      const bool normalise = sum > 1.0 + 1e-12;
      if (normalise) {
        p_mirror /= sum;
        p_transmit /= sum;
      }
      const double pick = rng.uniform();
      const bool mirror = pick < p_mirror, transmit = !mirror && pick < p_mirror + p_transmit;
      if (!mirror && !transmit) {
        tally.stopped += power;
        return;
      }
      if (events >= c_.params.specular_bounces) {
        tally.truncated += power;
        return;
      }
      const rgb w = mirror ? event.kr : event.kt;
      const bool grey = w.r == w.g && w.g == w.b && !normalise;
      const rgb next = grey ? power : power * w / (mirror ? p_mirror : p_transmit);
      tally.reweighted += next - power;
      power = next;
      vec3 origin;
      if (mirror) {
        d = reflect(d, n);
        origin = point + c_.offset * n_face;
        if (glm::dot(d, n_face) <= 0.0) {  // the shading normal sent it into the surface
          tally.stopped += power;
          return;
        }
      } else {
        d = *event.refracted;
        origin = point - c_.offset * n_face;
        if (glm::dot(d, n_face) >= 0.0) {
          tally.stopped += power;
          return;
        }
      }
      ++out.rays;
      const occlusion_scene::crossing hit = c_.occlusion->first_crossing(origin, origin + far * d);
      if (hit.triangle < 0) {
        tally.escaped += power;
        return;
      }
      e = hit.triangle;
      b = vec3(1.0 - hit.u - hit.v, hit.u, hit.v);
    }
  }

 private:
  const scene& s_;
  const form_factor_context& c_;
  const patch_mesh& mesh_;
};

}  // namespace

bool has_specular_materials(const scene& s) {
  return std::any_of(s.materials.begin(), s.materials.end(),
                     [](const material& m) { return any_positive(m.kr) || any_positive(m.kt); });
}

std::shared_ptr<const specular_surfaces> find_specular_surfaces(const scene& s, const patch_mesh& mesh,
                                                                const mirror_set* mirrors) {
  auto out = std::make_shared<specular_surfaces>();
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const material& m = s.materials[std::size_t(mesh.element_materials[e])];
    if (!any_positive(m.kr) && !any_positive(m.kt)) continue;
    (mirrors && mirrors->element_mirror[e] ? out->planar_mirror_elements : out->elements).push_back(int(e));
  }
  if (out->elements.empty()) return nullptr;  // planar mirrors alone: the images carry all
  return out;
}

void add(specular_tally& to, const specular_tally& from) {
  to.sent += from.sent;
  to.deposited += from.deposited;
  to.stopped += from.stopped;
  to.escaped += from.escaped;
  to.truncated += from.truncated;
  to.imaged += from.imaged;
  to.reweighted += from.reweighted;
  to.paths += from.paths;
}

namespace {

// `count` paths from the source toward `targets`, chosen in proportion to
// what they receive; their deposits go to `irradiance`.
std::uint64_t send_paths(const scene& s, const form_factor_context& context, const std::vector<int>& targets,
                         bool planar_first, const specular_source& source, std::uint64_t seed, int count,
                         std::vector<rgb>& irradiance, specular_tally& tally) {
  const patch_mesh& mesh = *context.mesh;
  if (count <= 0 || targets.empty()) return 0;
  const shooter* from = source.from;
  const double tolerance = 1e-9 * mesh.scene_diagonal;
  const double far = 4.0 * std::max(mesh.scene_diagonal, 1e-12);  // a sun's rays start beyond the scene
  const vec3 centre = from ? (from->corners[0] + from->corners[1] + from->corners[2]) / 3.0 : vec3(0.0);

  // How much each specular element receives, roughly: the choice of
  // targets. Elements wholly behind a shooter get nothing, exactly.
  std::vector<double> weight(targets.size(), 0.0);
  std::vector<std::uint8_t> reachable(targets.size(), 0);
  double largest = 0.0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const int e = targets[i];
    const std::array<vec3, 3> corners = element_corners(mesh, std::size_t(e));
    const vec3 c = (corners[0] + corners[1] + corners[2]) / 3.0;
    vec3 n = mesh.element_normals[std::size_t(e)];
    double f = 0.0;
    if (from) {
      if (glm::dot(n, centre - c) < 0.0) n = -n;  // glass and mirrors take light on either side
      for (const vec3& corner : corners)
        if (glm::dot(from->normal, corner - centre) > tolerance) reachable[i] = 1;
      if (reachable[i]) f = point_polygon_form_factor(c, n, from->corners);
    } else {
      reachable[i] = 1;
      const light_arrival a = light_at(*source.light, c, far);
      f = std::abs(glm::dot(n, a.to_light)) * channel_mean(a.irradiance);
    }
    weight[i] = mesh.element_areas[std::size_t(e)] * f;
    largest = std::max(largest, f);
  }
  // The floor: every reachable element keeps 1% of the largest estimate
  // (per area), so that a centre that sees nothing cannot starve an element
  // whose other parts do.
  const double floor = largest > 0.0 ? 0.01 * largest : 1.0;
  std::vector<double> cumulative(targets.size() + 1, 0.0);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (reachable[i]) weight[i] += floor * mesh.element_areas[std::size_t(targets[i])];
    cumulative[i + 1] = cumulative[i] + weight[i];
  }
  const double total = cumulative.back();
  if (!(total > 0.0)) return 0;

  const path_tracer tracer(s, context);
  constexpr std::size_t block = 256;
  const std::size_t blocks = (std::size_t(count) + block - 1) / block;
  std::vector<block_result> results(blocks);
  for_each_block(context.params.parallel, blocks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      block_result& out = results[k];
      const std::size_t last = std::min(std::size_t(count), (k + 1) * block);
      for (std::size_t i = k * block; i < last; ++i) {
        random_stream rng(seed, i);
        // Stratified over the paths in the choice of element.
        const double u = (double(i) + rng.uniform()) / double(count) * total;
        const std::size_t j = std::size_t(std::clamp<std::ptrdiff_t>(
            std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin() - 1, 0,
            std::ptrdiff_t(targets.size()) - 1));
        const int e = targets[j];
        const double p = weight[j] / total;
        if (!(p > 0.0)) continue;
        const glm::ivec3 t = mesh.elements[std::size_t(e)];
        const vec3 b = uniform_barycentric(rng.uniform(), rng.uniform());
        const vec3 y = b[0] * mesh.positions[t[0]] + b[1] * mesh.positions[t[1]] + b[2] * mesh.positions[t[2]];
        vec3 x(0.0);
        rgb arriving(0.0);  // a light's irradiance at y, facing it
        if (from) {
          const vec3 a = uniform_barycentric(rng.uniform(), rng.uniform());
          x = a[0] * from->corners[0] + a[1] * from->corners[1] + a[2] * from->corners[2];
        } else {
          const light_arrival a = light_at(*source.light, y, far);
          x = a.shadow_end;
          arriving = a.irradiance;
        }
        const vec3 to = y - x;
        const double r2 = glm::dot(to, to);
        if (!(r2 > 0.0)) continue;
        const double r = std::sqrt(r2);
        const vec3 d = to / r;
        const double cos_y = std::abs(glm::dot(mesh.element_normals[std::size_t(e)], d));
        const double area = mesh.element_areas[std::size_t(e)];
        rgb power;
        vec3 start = x;
        if (from) {
          const double cos_x = glm::dot(from->normal, d);
          if (!(cos_x > 0.0)) continue;
          power = source.radiosity * (cos_x * cos_y / (pi * r2) * from->area * area / (p * count));
          start += from->normal * context.offset;
        } else {
          power = arriving * (cos_y * area / (p * count));
        }
        // The segment must meet element e first (a little past y: the
        // float hit at the very end of a segment is not reliable).
        ++out.rays;
        const vec3 past = y + d * (2.0 * context.offset);
        const occlusion_scene::crossing hit = context.occlusion->first_crossing(start, past);
        if (hit.triangle != e) continue;
        ++out.tally.paths;
        out.tally.sent += power;
        tracer.follow(e, b, d, power, planar_first, rng, out);
      }
    }
  });
  std::uint64_t rays = 0;
  for (const block_result& r : results) {
    for (const deposit& dep : r.deposits) {
      const glm::ivec3 t = mesh.elements[std::size_t(dep.element)];
      for (int k = 0; k < 3; ++k) {
        const double share = context.vertex_areas[std::size_t(t[k])];
        if (share > 0.0) irradiance[std::size_t(t[k])] += dep.power * (dep.weights[k] / share);
      }
    }
    add(tally, r.tally);
    rays += r.rays;
  }
  return rays;
}

}  // namespace

std::uint64_t trace_specular_paths(const scene& s, const form_factor_context& context,
                                   const specular_surfaces& surfaces, const specular_source& source, std::uint64_t seed,
                                   std::vector<rgb>& irradiance, specular_tally& tally) {
  const int count = context.params.specular_paths;
  std::uint64_t rays = send_paths(s, context, surfaces.elements, false, source, seed, count, irradiance, tally);
  // Half as many by way of the planar mirrors: most of them reach a
  // diffuse surface straight from the mirror and end there at no cost
  // but their two rays.
  rays +=
      send_paths(s, context, surfaces.planar_mirror_elements, true, source, ~seed, (count + 1) / 2, irradiance, tally);
  return rays;
}

std::vector<rgb> specular_light_from_patches(const scene& s, const form_factor_context& context,
                                             const specular_surfaces* surfaces, const std::vector<rgb>& radiosity,
                                             std::uint64_t& seed, std::uint64_t& rays, std::uint64_t ray_budget,
                                             double* shot_fraction, bool images) {
  const patch_mesh& mesh = *context.mesh;
  std::vector<rgb> out(mesh.vertex_count(), rgb(0.0)), irradiance(mesh.vertex_count(), rgb(0.0));
  std::vector<double> f(mesh.vertex_count());
  specular_tally tally;
  // Patches in their order, or, with a budget, the most powerful first.
  std::vector<int> order;
  std::vector<double> power(mesh.patch_count(), 0.0);
  double total = 0.0;
  for (std::size_t p = 0; p < mesh.patch_count() && p < radiosity.size(); ++p)
    if (any_positive(radiosity[p])) {
      order.push_back(int(p));
      power[p] = (radiosity[p].r + radiosity[p].g + radiosity[p].b) * mesh.patch_areas[p];
      total += power[p];
    }
  if (ray_budget > 0)
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return power[std::size_t(a)] > power[std::size_t(b)]; });
  const std::uint64_t rays_before = rays;
  double shot = 0.0;
  bool all = true;
  for (const int p : order) {
    if (ray_budget > 0 && rays - rays_before >= ray_budget) {
      all = false;
      break;
    }
    const rgb b = radiosity[std::size_t(p)];
    shot += power[std::size_t(p)];
    const shooter from = patch_shooter(mesh, p);
    if (context.mirrors && images)
      for (const shooter& image : mirror_images(*context.mirrors, from, context.params.mirror_depth)) {
        rays += form_factors_by_rays(context, image, {}, f);
        for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
          out[v] += mesh.vertex_rho[v] * (f[v] * image.through.kr * b);
      }
    if (surfaces) {
      specular_source source;
      source.from = &from;
      source.radiosity = b;
      rays += trace_specular_paths(s, context, *surfaces, source, ++seed, irradiance, tally);
    }
  }
  // The patches shot stand in for those the budget left out.
  const double scale = all || shot <= 0.0 ? 1.0 : total / shot;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) out[v] = scale * (out[v] + mesh.vertex_rho[v] * irradiance[v]);
  if (shot_fraction) *shot_fraction = all || total <= 0.0 ? 1.0 : shot / total;
  return out;
}

std::vector<rgb> specular_light_from_sources(const scene& s, const form_factor_context& context,
                                             const specular_surfaces* surfaces, std::uint64_t& rays, bool patch_images,
                                             bool light_images) {
  const patch_mesh& mesh = *context.mesh;
  std::uint64_t seed = context.params.seed * 0x9E3779B97F4A7C15ull;
  // Emitting patches: their elements' area-weighted mean emission.
  std::vector<rgb> emission(mesh.patch_count(), rgb(0.0));
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    const rgb mean = (mesh.vertex_emission[t[0]] + mesh.vertex_emission[t[1]] + mesh.vertex_emission[t[2]]) / 3.0;
    emission[std::size_t(mesh.element_patches[e])] += mean * mesh.element_areas[e];
  }
  for (std::size_t p = 0; p < mesh.patch_count(); ++p)
    emission[p] = mesh.patch_areas[p] > 0.0 ? emission[p] / mesh.patch_areas[p] : rgb(0.0);
  std::vector<rgb> out =
      specular_light_from_patches(s, context, surfaces, emission, seed, rays, 0, nullptr, patch_images);
  std::vector<rgb> irradiance(mesh.vertex_count(), rgb(0.0));
  specular_tally tally;
  for (const punctual_light& light : s.lights)
    if (surfaces) {
      specular_source source;
      source.light = &light;
      rays += trace_specular_paths(s, context, *surfaces, source, ++seed, irradiance, tally);
    }
  if (context.mirrors && light_images) {
    const std::vector<rgb> mirrored =
        mirrored_point_light_radiosity(s, mesh, context, context.params.mirror_depth, rays);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) out[v] += mirrored[v];
  }
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) out[v] += mesh.vertex_rho[v] * irradiance[v];
  return out;
}

}  // namespace bounce
