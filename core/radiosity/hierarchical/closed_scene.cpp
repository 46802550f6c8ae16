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

void update_normalizer(hierarchical_solver& solver) {
  const std::size_t n = solver.mesh().element_count();
  std::vector<double>& normalizer = solver.hierarchy.normalizer;
  normalizer.assign(n, 1.0);
  if (!solver.progress.closed) return;
  // The form-factor sum of each element: its irradiance when every node has radiosity 1.
  std::vector<rgb> ones(n, rgb(1.0)), sum;
  gather_push(solver, ones, sum);
  for (std::size_t e = 0; e < n; ++e)
    if (sum[e].r > 0.0) normalizer[e] = 1.0 / sum[e].r;
}

}  // namespace bounce
