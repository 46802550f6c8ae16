#include "radiosity/transfer/mirror_images.h"

#include <algorithm>
#include <atomic>
#include <map>
#include <utility>

#include "base/parallel.h"
#include "radiosity/transfer/occlusion.h"
#include "scene/lights.h"

namespace bounce {
namespace {

bool reflects_only(const material& m) {
  return (m.kr.r > 0.0 || m.kr.g > 0.0 || m.kr.b > 0.0) && m.kt == rgb(0.0);
}

// Signed distances below this (scene units) count as in the plane.
double plane_tolerance(const patch_mesh& mesh) {
  return 1e-6 * mesh.scene_diagonal;
}

mirror_path prepend(const mirror_path& path, int mirror, const rgb& kr) {
  mirror_path out;
  out.count = path.count + 1;
  out.mirrors[0] = mirror;
  for (int i = 0; i < path.count; ++i) out.mirrors[i + 1] = path.mirrors[i];
  out.kr = path.kr * kr;
  return out;
}

struct image_search {
  const mirror_set& set;
  int depth;
  double tolerance;

  // Whether all of `points` lie in front of mirror m (on the plane allowed),
  // some strictly.
  bool in_front(const planar_mirror& m, std::span<const vec3> points) const {
    double most = 0.0;
    for (const vec3& p : points) {
      const double d = m.side(p);
      if (d < -tolerance) return false;
      most = std::max(most, d);
    }
    return most > tolerance;
  }

  void extend(const shooter& s, std::vector<shooter>& out) const {
    if (s.through.count >= depth) return;
    const int last = s.through.count > 0 ? s.through.mirrors[0] : -1;
    const vec3 centroid = (s.corners[0] + s.corners[1] + s.corners[2]) / 3.0;
    for (int m = 0; m < int(set.mirrors.size()); ++m) {
      if (m == last) continue;
      const planar_mirror& mirror = set.mirrors[std::size_t(m)];
      if (!in_front(mirror, s.corners)) continue;
      // The shooter emits from its front: it must face some of the mirror.
      const bool faces = std::any_of(mirror.corners.begin(), mirror.corners.end(),
                                     [&](const vec3& c) { return glm::dot(s.normal, c - centroid) > tolerance; });
      if (!faces) continue;
      shooter image = s;
      // Reflection turns the winding over: swap two corners to keep it
      // counter-clockwise seen from the (reflected) front.
      image.corners = {mirror.reflect_point(s.corners[0]), mirror.reflect_point(s.corners[2]),
                       mirror.reflect_point(s.corners[1])};
      image.normal = mirror.reflect_direction(s.normal);
      image.through = prepend(s.through, m, mirror.kr);
      out.push_back(image);
      extend(image, out);
    }
  }

  void extend(const light_image& p, std::vector<light_image>& out) const {
    if (p.through.count >= depth) return;
    const int last = p.through.count > 0 ? p.through.mirrors[0] : -1;
    for (int m = 0; m < int(set.mirrors.size()); ++m) {
      if (m == last) continue;
      const planar_mirror& mirror = set.mirrors[std::size_t(m)];
      const bool lit = p.light.type == light_type::sun ? glm::dot(mirror.normal, p.light.direction) < 0.0
                                                       : in_front(mirror, std::span(&p.light.position, 1));
      if (!lit) continue;
      light_image image{p.light, prepend(p.through, m, mirror.kr)};
      image.light.position = mirror.reflect_point(p.light.position);
      image.light.direction = mirror.reflect_direction(p.light.direction);
      out.push_back(image);
      extend(image, out);
    }
  }
};

}  // namespace

std::shared_ptr<const mirror_set> find_planar_mirrors(const scene& s, const patch_mesh& mesh) {
  const double tolerance = plane_tolerance(mesh);
  struct plane_group {
    vec3 normal;
    double offset;
    std::vector<int> elements;
  };
  struct surface_group {
    bool planar = true;
    std::vector<plane_group> planes;
  };
  std::map<std::pair<int, int>, surface_group> groups;  // by (surface, material): a stable order
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const int m = mesh.element_materials[e];
    if (m < 0 || std::size_t(m) >= s.materials.size() || !reflects_only(s.materials[std::size_t(m)])) continue;
    surface_group& group = groups[{mesh.element_surfaces[e], m}];
    const vec3 n = mesh.element_normals[e];
    const glm::ivec3 t = mesh.elements[e];
    // Smooth normals mean a curved surface, whatever its facets: traced.
    for (int k = 0; k < 3; ++k)
      if (glm::dot(mesh.normals[t[k]], n) < 1.0 - 1e-9) group.planar = false;
    if (!group.planar) continue;
    const double offset = glm::dot(n, mesh.positions[t[0]]);
    auto same = std::find_if(group.planes.begin(), group.planes.end(), [&](const plane_group& g) {
      return glm::dot(g.normal, n) > 1.0 - 1e-9 && std::abs(g.offset - offset) < tolerance;
    });
    if (same == group.planes.end()) {
      group.planes.push_back({n, offset, {}});
      same = group.planes.end() - 1;
    }
    same->elements.push_back(int(e));
  }
  auto set = std::make_shared<mirror_set>();
  set->element_mirror.assign(mesh.element_count(), 0);
  for (const auto& [key, group] : groups) {
    if (!group.planar || group.planes.size() > std::size_t(max_planes_per_mirror_surface)) continue;
    for (const plane_group& plane : group.planes) {
      if (set->mirrors.size() >= std::size_t(max_planar_mirrors)) break;
      planar_mirror mirror;
      mirror.normal = plane.normal;
      mirror.offset = plane.offset;
      mirror.surface = key.first;
      mirror.material = key.second;
      mirror.kr = s.materials[std::size_t(key.second)].kr;
      std::map<int, int> index;  // mesh vertex -> the outline's own
      std::vector<glm::ivec3> triangles;
      for (int e : plane.elements) {
        glm::ivec3 t;
        for (int k = 0; k < 3; ++k) {
          const int v = mesh.elements[std::size_t(e)][k];
          auto [it, added] = index.emplace(v, int(mirror.corners.size()));
          if (added) mirror.corners.push_back(mesh.positions[std::size_t(v)]);
          t[k] = it->second;
        }
        triangles.push_back(t);
        mirror.area += mesh.element_areas[std::size_t(e)];
        set->element_mirror[std::size_t(e)] = 1;
      }
      mirror.outline = std::make_shared<occlusion_scene>(mirror.corners, triangles);
      set->mirrors.push_back(std::move(mirror));
    }
  }
  set->tolerance = tolerance;
  if (set->mirrors.empty()) return nullptr;
  return set;
}

std::vector<shooter> mirror_images(const mirror_set& mirrors, const shooter& from, int depth) {
  std::vector<shooter> out;
  const image_search search{mirrors, std::clamp(depth, 0, max_mirror_depth), mirrors.tolerance};
  search.extend(from, out);
  return out;
}

std::vector<light_image> mirror_images(const mirror_set& mirrors, const punctual_light& light, int depth) {
  std::vector<light_image> out;
  const image_search search{mirrors, std::clamp(depth, 0, max_mirror_depth), mirrors.tolerance};
  search.extend(light_image{light, {}}, out);
  return out;
}

bool visible_through_mirrors(const form_factor_context& context, const mirror_path& path, const vec3& from,
                             const vec3& to) {
  const mirror_set& set = *context.mirrors;
  vec3 a = from, target = to;
  for (int i = 0; i < path.count; ++i) {
    const planar_mirror& mirror = set.mirrors[std::size_t(path.mirrors[i])];
    const double sa = mirror.side(a), st = mirror.side(target);
    if (!(sa > 0.0 && st < 0.0)) return false;               // the light must come through the plane from the front
    if (!mirror.outline->occluded(a, target)) return false;  // ... inside the mirror
    const vec3 point = a + (target - a) * (sa / (sa - st)) + mirror.normal * context.offset;
    if (context.occlusion->occluded(a, point)) return false;
    a = point;
    target = mirror.reflect_point(target);
  }
  return !context.occlusion->occluded(a, target);
}

std::vector<light_image> light_images(const scene& s, const mirror_set& mirrors, int depth) {
  std::vector<light_image> images;
  for (const punctual_light& light : s.lights) {
    const std::vector<light_image> of_light = mirror_images(mirrors, light, depth);
    images.insert(images.end(), of_light.begin(), of_light.end());
  }
  return images;
}

rgb mirrored_light_irradiance(const form_factor_context& context, const std::vector<light_image>& images, const vec3& p,
                              const vec3& n, std::uint64_t& rays) {
  // A sun's image: the shadow ray ends beyond the scene, 4 diagonals off,
  // so it crosses the mirror's plane as the light does.
  const double far = 4.0 * std::max(context.mesh->scene_diagonal, 1e-12);
  rgb irradiance(0.0);
  for (const light_image& im : images) {
    const light_arrival a = light_at(im.light, p, far);
    const double cosine = glm::dot(n, a.to_light);
    if (!(cosine > 0.0) || !any_positive(a.irradiance)) continue;
    rays += std::uint64_t(im.through.count + 1);
    if (!visible_through_mirrors(context, im.through, p + n * context.offset, a.shadow_end)) continue;
    irradiance += im.through.kr * a.irradiance * cosine;
  }
  return irradiance;
}

std::vector<rgb> mirrored_point_light_radiosity(const scene& s, const patch_mesh& mesh,
                                                const form_factor_context& context, int depth, std::uint64_t& rays,
                                                std::size_t first) {
  std::vector<rgb> out(mesh.vertex_count(), rgb(0.0));
  if (!context.mirrors || depth <= 0) return out;
  const std::vector<light_image> images = light_images(s, *context.mirrors, depth);
  if (images.empty()) return out;
  std::atomic<std::uint64_t> cast{0};
  auto light_vertices = [&](std::size_t begin, std::size_t end) {
    std::uint64_t local = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t v = first + i;
      out[v] = mesh.vertex_rho[v] *
               mirrored_light_irradiance(context, images, mesh.receive_points[v], mesh.normals[v], local);
    }
    cast += local;
  };
  for_each_block(context.params.parallel, mesh.vertex_count() - std::min(first, mesh.vertex_count()), 256,
                 light_vertices);
  rays += cast;
  return out;
}

}  // namespace bounce
