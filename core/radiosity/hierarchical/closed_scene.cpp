#include "radiosity/hierarchical/closed_scene.h"

#include <atomic>
#include <cmath>
#include <numbers>

#include "base/parallel.h"
#include "base/random_stream.h"
#include "radiosity/hierarchical/transport.h"
#include "radiosity/transfer/occlusion.h"

namespace bounce {

bool scene_is_closed(const hierarchical_solver& solver) {
  const patch_mesh& mesh = solver.mesh();
  const cluster_tree& tree = solver.hierarchy.tree;
  const std::size_t count = mesh.element_count();
  if (count == 0) return false;
  const std::size_t stride = std::max<std::size_t>(1, count / 4096);
  std::atomic<bool> escaped{false};
  const double far = 4.0 * mesh.scene_diagonal;
  for_each_block(solver.params.parallel, (count + stride - 1) / stride, 64, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e && !escaped; ++k) {
      const std::size_t el = k * stride;
      const cluster_node& leaf = tree.nodes[std::size_t(tree.leaf_of_element[el])];
      const vec3 n = leaf.normal;
      const vec3 a = glm::normalize(std::abs(n.x) > 0.9 ? glm::cross(n, vec3(0, 1, 0)) : glm::cross(n, vec3(1, 0, 0)));
      const vec3 c = glm::cross(n, a);
      hash_chain random{mix64(solver.params.seed + el)};
      for (int r = 0; r < 8; ++r) {
        // Cosine-distributed directions.
        const double u = (r + random.uniform()) / 8.0, phi = 2.0 * std::numbers::pi * random.uniform();
        const double s = std::sqrt(u);
        const vec3 dir = n * std::sqrt(std::max(0.0, 1.0 - u)) + a * (s * std::cos(phi)) + c * (s * std::sin(phi));
        const vec3 from = leaf.centroid + n * solver.context.offset;
        if (!solver.context.occlusion->occluded(from, from + dir * far)) {
          escaped = true;
          break;
        }
      }
    }
  });
  return !escaped;
}

closed_scale closed_scale_for(double emitters, double rest) {
  if (rest > 0.0 && emitters < 1.0) return {(1.0 - emitters) / rest, 1.0};
  const double sum = emitters + rest;
  return sum > 0.0 ? closed_scale{1.0 / sum, 1.0 / sum} : closed_scale{};
}

void update_normalizer(hierarchical_solver& solver, const std::vector<rgb>& node_e) {
  const std::size_t n = solver.mesh().element_count();
  std::vector<closed_scale>& normalizer = solver.hierarchy.normalizer;
  normalizer.assign(n, closed_scale{});
  link_hierarchy& h = solver.hierarchy;
  clear_links(h.emitter_links, h.tree.nodes.size());
  if (!solver.progress.closed) return;
  // The links whose source emits carry the direct light, found with care
  // (the emitter's own strata, its visibility partial or not); the
  // shortfall of the form-factor sum is the coarse indirect links'.
  // Spread over every link, it made the direct light too bright where
  // the shortfall was large (boxes in a crowded room, 10-12%).
  for (const hierarchy_link& link : h.links.links)
    if (node_emits(node_e, link.source)) h.emitter_links.links.push_back(link);
  index_links(h.emitter_links, h.tree.nodes.size());
  // The form-factor sums: each element's irradiance when every node has
  // radiosity 1, through all the plain links and through the emitters'.
  std::vector<rgb> ones(n, rgb(1.0)), sum, emitted;
  gather_push(solver, ones, sum, nullptr, &emitted);
  for (std::size_t e = 0; e < n; ++e) normalizer[e] = closed_scale_for(emitted[e].r, sum[e].r - emitted[e].r);
}

}  // namespace bounce
