#include "radiosity/hierarchical/sources.h"

#include "base/check.h"
#include "radiosity/transfer/mirror_images.h"
#include "radiosity/transfer/point_lights.h"

namespace bounce {

void rebuild_for_mesh(hierarchical_solver& solver, cluster_tree tree) {
  const patch_mesh& mesh = solver.mesh();
  const scene& s = *solver.source;
  link_hierarchy& h = solver.hierarchy;
  element_sources& src = solver.sources;
  BOUNCE_CHECK_EQ(tree.leaf_of_element.size(), mesh.element_count());
  solver.context.mesh = &mesh;
  h.tree = std::move(tree);
  const std::size_t nodes = h.tree.nodes.size();
  h.cube_slot.assign(nodes, -1);
  int slots = 0;
  for (std::size_t i = 0; i < nodes; ++i)
    if (!h.tree.nodes[i].oriented) h.cube_slot[i] = slots++;
  solver.buffers.node_b.resize(nodes);
  solver.buffers.gathered.resize(nodes);
  solver.buffers.bins.resize(std::size_t(slots));
  clear_links(h.links, nodes);
  clear_links(h.mirror_links, nodes);
  clear_links(h.emitter_links, nodes);
  solver.split_marks.clear();

  const std::size_t n = mesh.element_count();
  h.rho.resize(n);
  src.emission.resize(n);
  src.lamp.assign(n, rgb(0.0));
  h.normalizer.assign(n, closed_scale{});
  BOUNCE_CHECK(src.specular_lamp.empty() || src.specular_lamp.size() == n);
  src.light_images = solver.context.mirrors
                         ? light_images(s, *solver.context.mirrors, solver.context.params.mirror_depth)
                         : std::vector<light_image>();
  src.mirrored_lamp.assign(src.light_images.empty() ? 0 : n, rgb(0.0));
  std::uint64_t rays = 0;
  for (std::size_t e = 0; e < n; ++e) {
    h.rho[e] = element_mean(mesh, mesh.vertex_rho, e);
    src.emission[e] = element_mean(mesh, mesh.vertex_emission, e);
    const cluster_node& leaf = h.tree.nodes[std::size_t(h.tree.leaf_of_element[e])];
    if (has_lights_beyond_surfaces(s))
      src.lamp[e] = h.rho[e] * point_light_irradiance(s, solver.context, leaf.centroid, leaf.normal, rays);
    if (!src.light_images.empty()) {
      src.mirrored_lamp[e] =
          h.rho[e] * mirrored_light_irradiance(solver.context, src.light_images, leaf.centroid, leaf.normal, rays);
      src.lamp[e] += src.mirrored_lamp[e];
    }
    if (!src.specular_lamp.empty()) src.lamp[e] += src.specular_lamp[e];
  }
  solver.progress.rays += rays;
  src.emitted_power = 0.0;
  for (std::size_t e = 0; e < n; ++e)
    src.emitted_power += channel_sum(src.emission[e] + src.lamp[e]) * mesh.element_areas[e];
}

std::vector<rgb> right_hand_side(const hierarchical_solver& solver) {
  const element_sources& src = solver.sources;
  std::vector<rgb> b(src.emission.size());
  for (std::size_t e = 0; e < b.size(); ++e) b[e] = src.emission[e] + src.lamp[e];
  return b;
}

rgb direct_lamp(const hierarchical_solver& solver, std::size_t e) {
  const element_sources& src = solver.sources;
  rgb direct = src.lamp[e];
  if (!src.specular_lamp.empty()) direct -= src.specular_lamp[e];
  if (!src.mirrored_lamp.empty()) direct -= src.mirrored_lamp[e];
  return direct;
}

}  // namespace bounce
