#include "radiosity/transfer/buried_vertices.h"

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "base/check.h"
#include "base/directions.h"
#include "base/parallel.h"

namespace bounce {
namespace {

// True when every probe ray from the vertex meets the back of an occluder.
bool is_buried(const vec3& point, const vec3& normal, const patch_mesh& occluders, const occlusion_scene& scene,
               double offset, double reach) {
  vec3 t, b;
  orthonormal_basis(normal, t, b);
  const double tilt = 50.0 * std::numbers::pi / 180.0;
  const vec3 from = point + offset * normal;
  for (int k = 0; k < buried_probe_rays; ++k) {
    vec3 d = normal;
    if (k > 0) {
      const double phi = 2.0 * std::numbers::pi * (k - 1) / (buried_probe_rays - 1);
      d = std::cos(tilt) * normal + std::sin(tilt) * (std::cos(phi) * t + std::sin(phi) * b);
    }
    const occlusion_scene::crossing hit = scene.first_crossing(from, from + reach * d);
    if (hit.triangle < 0 || std::size_t(hit.triangle) >= occluders.element_count()) return false;
    if (glm::dot(occluders.element_normals[std::size_t(hit.triangle)], d) <= 0.0) return false;  // a front
  }
  return true;
}

}  // namespace

void find_buried_vertices(const patch_mesh& mesh, const patch_mesh& occluders, const occlusion_scene& scene,
                          double offset, std::vector<bool>& buried) {
  const std::size_t known = std::min(buried.size(), mesh.vertex_count());
  buried.resize(mesh.vertex_count(), false);
  const std::size_t fresh = mesh.vertex_count() - known;
  std::vector<char> found(fresh, 0);  // vector<bool> packs bits: not safe to write from threads
  const double reach = 2.0 * mesh.scene_diagonal;
  for_each_block(true, fresh, 256, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t v = known + i;
      found[i] = is_buried(mesh.receive_points[v], mesh.normals[v], occluders, scene, offset, reach);
    }
  });
  for (std::size_t i = 0; i < fresh; ++i) buried[known + i] = found[i] != 0;
}

void fill_buried_vertices(const patch_mesh& mesh, const std::vector<bool>& buried,
                          std::initializer_list<std::span<rgb>> arrays) {
  for (const std::span<rgb>& values : arrays) BOUNCE_CHECK_EQ(values.size(), mesh.vertex_count());
  if (buried.size() != mesh.vertex_count()) return;
  std::vector<std::size_t> touching;  // elements with a buried corner
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    if (buried[std::size_t(t[0])] || buried[std::size_t(t[1])] || buried[std::size_t(t[2])]) touching.push_back(e);
  }
  if (touching.empty()) return;
  std::vector<char> known(mesh.vertex_count());
  for (std::size_t v = 0; v < known.size(); ++v) known[v] = !buried[v];
  // Per round: each vertex still unknown and the weights of its known neighbours.
  std::map<std::size_t, std::vector<std::pair<std::size_t, double>>> round;
  for (int pass = 0; pass < 16; ++pass) {
    round.clear();
    for (std::size_t e : touching) {
      const glm::ivec3 t = mesh.elements[e];
      for (int k = 0; k < 3; ++k) {
        const std::size_t v = std::size_t(t[k]);
        if (known[v]) continue;
        for (int j = 1; j < 3; ++j)
          if (const std::size_t u = std::size_t(t[(k + j) % 3]); known[u])
            round[v].emplace_back(u, mesh.element_areas[e]);
      }
    }
    if (round.empty()) break;
    std::vector<std::size_t> filled;
    for (const auto& [v, from] : round) {
      double weight = 0.0;
      for (const auto& [u, w] : from) weight += w;
      if (!(weight > 0.0)) continue;
      filled.push_back(v);
      for (const std::span<rgb>& values : arrays) {
        rgb sum(0.0);
        for (const auto& [u, w] : from) sum += w * values[u];
        values[v] = sum / weight;
      }
    }
    if (filled.empty()) break;
    for (std::size_t v : filled) known[v] = 1;
  }
}

}  // namespace bounce
