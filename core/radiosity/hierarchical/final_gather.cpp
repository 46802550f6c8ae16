#include "radiosity/hierarchical/final_gather.h"

#include <atomic>

#include "base/parallel.h"
#include "radiosity/hierarchical/node_kernels.h"
#include "radiosity/hierarchical/transport.h"
#include "radiosity/transfer/form_factor.h"

namespace bounce {

std::uint64_t final_gather_cost(const hierarchical_solver& solver) {
  const link_hierarchy& h = solver.hierarchy;
  const cluster_tree& tree = h.tree;
  std::vector<std::uint64_t> chain(tree.nodes.size(), 0);
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    chain[i] =
        h.links.count_of(i) + h.mirror_links.count_of(i) + (i > 0 ? chain[std::size_t(tree.nodes[i].parent)] : 0);
    if (tree.nodes[i].leaf()) total += chain[i];
  }
  return total;
}

bool final_gather(hierarchical_solver& solver) {
  if (final_gather_cost(solver) > solver.params.gather_budget) return false;
  const link_hierarchy& h = solver.hierarchy;
  const cluster_tree& tree = h.tree;
  const patch_mesh& mesh = solver.mesh();
  std::vector<rgb> node_b(tree.nodes.size()), node_e(tree.nodes.size());
  std::vector<std::array<rgb, 6>> sent_b, sent_e;
  pull(solver, solver.light.total, node_b, &sent_b);
  pull(solver, solver.sources.emission, node_e, &sent_e);
  // Per link from an inner node: its strata estimate over the disc
  // estimate at its receiver's centre.
  std::vector<float> correction(h.links.size(), 1.0f);
  if (!solver.progress.closed)  // closed scenes' links carry the disc estimate itself
    for_each_block(solver.params.parallel, h.links.size(), 4096, [&](std::size_t b, std::size_t end) {
      for (std::size_t l = b; l < end; ++l) {
        const hierarchy_link& link = h.links.links[l];
        const cluster_node& r = tree.nodes[std::size_t(link.receiver)];
        const cluster_node& s = tree.nodes[std::size_t(link.source)];
        if (s.leaf() || !r.oriented) continue;
        const double at_centre = disc_factor(s, r.centroid, &r.normal);
        if (at_centre > 0.0) correction[l] = float(double(link.factor) / at_centre);
      }
    });
  const std::size_t n = mesh.element_count();
  element_light& out = solver.gathered;
  out.total.assign(n, rgb(0.0));
  out.direct.assign(n, rgb(0.0));
  out.mirrored.assign(n, rgb(0.0));
  std::atomic<std::uint64_t> evaluations{0};
  for_each_block(solver.params.parallel, n, 256, [&](std::size_t b, std::size_t end) {
    std::uint64_t count = 0;
    for (std::size_t e = b; e < end; ++e) {
      const cluster_node& leaf = tree.nodes[std::size_t(tree.leaf_of_element[e])];
      rgb sum(0.0), direct(0.0);
      double factors = 0.0;
      for (int a = tree.leaf_of_element[e]; a >= 0; a = tree.nodes[std::size_t(a)].parent) {
        for (std::size_t l = h.links.offsets[std::size_t(a)]; l < h.links.offsets[std::size_t(a) + 1]; ++l) {
          const hierarchy_link& link = h.links.links[l];
          const cluster_node& s = tree.nodes[std::size_t(link.source)];
          ++count;
          double f = 0.0, send = 0.0;
          vec3 dir(0.0);
          if (s.leaf()) {
            f = point_polygon_form_factor(leaf.centroid, leaf.normal, element_corners(mesh, std::size_t(s.element)));
          } else {
            f = std::min(1.0, disc_factor(s, leaf.centroid, &leaf.normal, dir, send) * double(correction[l]));
          }
          f *= double(link.visibility);
          if (!(f > 0.0)) continue;
          factors += f;
          sum += f * sent_radiosity(solver, node_b, sent_b, link.source, -dir, send);
          direct += f * sent_radiosity(solver, node_e, sent_e, link.source, -dir, send);
        }
      }
      rgb mirrored(0.0), mirrored_direct(0.0);
      for (int a = tree.leaf_of_element[e]; a >= 0; a = tree.nodes[std::size_t(a)].parent) {
        for (const mirror_link& m : h.mirror_links.of(std::size_t(a))) {
          const mirror_chain& chain = h.chains[std::size_t(m.chain)];
          const cluster_node& s = tree.nodes[std::size_t(m.link.source)];
          ++count;
          vec3 dir;
          double send = 0.0;
          double f = disc_factor(s, leaf.centroid, &leaf.normal, dir, send, &chain);
          if (dir == vec3(0.0)) continue;  // no direction
          const vec3 from = chain.source_direction(-dir);
          if (s.leaf()) {
            std::array<vec3, 3> polygon = element_corners(mesh, std::size_t(s.element));
            for (vec3& corner : polygon) corner = chain.image(corner);
            f = point_polygon_form_factor(leaf.centroid, leaf.normal, polygon);
          }
          f *= double(m.link.visibility);
          if (!(f > 0.0)) continue;
          mirrored += f * chain.path.kr * sent_radiosity(solver, node_b, sent_b, m.link.source, from, send);
          mirrored_direct += f * chain.path.kr * sent_radiosity(solver, node_e, sent_e, m.link.source, from, send);
        }
      }
      // The normaliser is for the plain links alone: a mirror's solid
      // angle is counted once, by the links to the mirror itself.
      const double scale = solver.progress.closed && factors > 0.0 ? 1.0 / factors : 1.0;
      out.total[e] = h.rho[e] * (sum * scale + mirrored);
      out.direct[e] = h.rho[e] * (direct * scale);
      out.mirrored[e] = h.rho[e] * mirrored_direct;
    }
    evaluations += count;
  });
  solver.progress.gather_evaluations += evaluations.load();
  return true;
}

}  // namespace bounce
