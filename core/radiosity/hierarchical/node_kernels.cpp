#include "radiosity/hierarchical/node_kernels.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "radiosity/transfer/form_factor.h"

namespace bounce {

double disc_factor(const cluster_node& s, const vec3& p, const vec3* n, vec3& towards, double& send,
                   const mirror_chain* chain) {
  const vec3 d = (chain ? chain->image(s.centroid) : s.centroid) - p;
  const double r2 = glm::dot(d, d);
  towards = r2 > 0.0 ? d / std::sqrt(r2) : vec3(0.0);
  const double receive = n ? std::max(0.0, glm::dot(*n, towards)) : 1.0;
  send = projected_area(s, chain ? chain->source_direction(-towards) : -towards);
  return std::min(1.0, receive * send / (std::numbers::pi * r2 + send));
}

double disc_factor(const cluster_node& s, const vec3& p, const vec3* n, const mirror_chain* chain) {
  vec3 towards;
  double send = 0.0;
  return disc_factor(s, p, n, towards, send, chain);
}

double strata_factor(const cluster_tree& tree, const patch_mesh& mesh, int s, const vec3& p, const vec3& n) {
  constexpr int strata = cluster_tree::sample_strata;
  const double share = tree.nodes[std::size_t(s)].area / strata;
  double sum = 0.0;
  for (const int element : tree.strata[std::size_t(s)]) {
    const std::array<vec3, 3> polygon = element_corners(mesh, std::size_t(element));
    const vec3& normal = mesh.element_normals[std::size_t(element)];
    if (glm::dot(normal, p - polygon[0]) <= 0.0) continue;  // faces away
    const double area = mesh.element_areas[std::size_t(element)];
    const vec3 d = (polygon[0] + polygon[1] + polygon[2]) / 3.0 - p;
    const double r2 = glm::dot(d, d);
    if (area < 0.01 * std::numbers::pi * r2) {
      // Small as seen from p: the point-to-point kernel at its centre.
      const double cosines = std::max(0.0, glm::dot(n, d)) * std::max(0.0, -glm::dot(normal, d)) / r2;
      sum += cosines / (std::numbers::pi * r2) * share;
    } else {
      sum += point_polygon_form_factor(p, n, polygon) * share / area;
    }
  }
  return std::min(1.0, sum);
}

double factor_variation(const cluster_tree& tree, const patch_mesh& mesh, int r_index, int s_index) {
  const cluster_node& r = tree.nodes[std::size_t(r_index)];
  const cluster_node& s = tree.nodes[std::size_t(s_index)];
  std::array<vec3, 3> polygon{};
  if (s.leaf()) polygon = element_corners(mesh, std::size_t(s.element));
  auto factor_at = [&](const vec3& p) {
    if (s.leaf()) return point_polygon_form_factor(p, r.normal, polygon);
    return disc_factor(s, p, &r.normal);
  };
  double lo = INFINITY, hi = -INFINITY;
  auto add = [&](const vec3& p) {
    const double f = factor_at(p);
    if (!std::isfinite(f)) return;
    lo = std::min(lo, f);
    hi = std::max(hi, f);
  };
  add(r.centroid);
  for (const int element : tree.strata[std::size_t(r_index)]) add(element_centroid(mesh, std::size_t(element)));
  return hi > lo ? hi - lo : 0.0;
}

}  // namespace bounce
