#include "radiosity/hierarchical/element_refinement.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "base/check.h"
#include "base/parallel.h"
#include "radiosity/hierarchical/sources.h"
#include "radiosity/hierarchical/view_importance.h"
#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/mirror_images.h"
#include "radiosity/transfer/point_lights.h"

namespace bounce {
namespace {

// Per element of the refined mesh, the value its element had.
template <typename value>
std::vector<value> carried(const std::vector<value>& old, const std::vector<int>& from) {
  std::vector<value> out(from.size());
  for (std::size_t e = 0; e < out.size(); ++e) out[e] = old[std::size_t(from[e])];
  return out;
}

// With a view, an element it sees large may be split below the default
// minimum edge (an eighth of the starting size, which follows the scene's
// size), down to an edge that spans 2 pixels of the camera's picture and
// 4 of its importance rays (their resolution), but not below an eighth of
// that minimum. A minimum given stays.
constexpr double seen_edge_pixels = 2.0, seen_edge_rays = 4.0;

double element_min_edge(const hierarchical_solver& solver, std::size_t element) {
  const double min_edge = solver.meshes.min_edge;
  if (solver.view.seen.empty() || !solver.meshes.min_edge_follows_view) return min_edge;
  const double density = solver.view.seen[std::size_t(solver.meshes.input_element[element])];  // rays per unit area
  if (!(density > 0.0)) return min_edge;
  const double rays = std::max(seen_edge_rays, seen_edge_pixels * solver.view.rays_per_pixel);
  return std::clamp(rays / std::sqrt(density), min_edge / 8.0, min_edge);
}

}  // namespace

int bisections_needed(const hierarchical_solver& solver, const std::vector<rgb>& node_b, double tolerance, int i, int j,
                      double factor, float visibility, const mirror_chain* chain) {
  if (!solver.params.split_elements) return 0;
  const cluster_node& r = solver.hierarchy.tree.nodes[std::size_t(i)];
  const cluster_node& s = solver.hierarchy.tree.nodes[std::size_t(j)];
  const patch_mesh& mesh = solver.mesh();
  const double transfer = r.area * channel_max(node_b[std::size_t(j)]) * (chain ? channel_max(chain->path.kr) : 1.0) *
                          receiver_weight(solver, i);
  if (!(factor * transfer > tolerance)) return 0;  // nothing this pair carries can matter
  double error = 0.0;
  if (visibility > 0.0f && visibility < 1.0f) {
    error = solver.params.partial_factor * factor * transfer;
  } else if (visibility > 0.0f) {
    std::array<vec3, 3> polygon = element_corners(mesh, std::size_t(s.element));
    if (chain)
      for (vec3& x : polygon) x = chain->image(x);
    const std::array<vec3, 3> corners = element_corners(mesh, std::size_t(r.element));
    double lo = factor, hi = factor;
    for (const vec3& corner : corners) {
      // Towards the corners, not at them: a corner may touch the source.
      const vec3 p = r.centroid + 0.75 * (corner - r.centroid);
      const double f = point_polygon_form_factor(p, r.normal, polygon);
      if (std::isfinite(f)) {
        lo = std::min(lo, f);
        hi = std::max(hi, f);
      }
    }
    error = (hi - lo) * transfer;
  }
  const double ratio = error / tolerance;
  if (!(ratio > 1.0) ||
      !(element_longest_edge(mesh, std::size_t(r.element)) > element_min_edge(solver, std::size_t(r.element))))
    return 0;
  return std::clamp(int(std::ceil(std::log2(ratio))), 1, solver.params.max_bisections);
}

std::vector<std::pair<int, int>> lamp_marks(const hierarchical_solver& solver, double tolerance,
                                            std::uint64_t& rays_cast) {
  const scene& s = *solver.source;
  if (!solver.params.split_elements || s.lights.empty()) return {};
  const patch_mesh& mesh = solver.mesh();
  const element_sources& src = solver.sources;
  std::vector<std::vector<std::pair<int, int>>> parts((mesh.element_count() + 255) / 256);
  std::atomic<std::uint64_t> cast{0};
  for_each_block(solver.params.parallel, parts.size(), 1, [&](std::size_t b, std::size_t end) {
    std::uint64_t rays = 0;
    for (std::size_t part = b; part < end; ++part)
      for (std::size_t e = part * 256; e < std::min(mesh.element_count(), (part + 1) * 256); ++e) {
        const int leaf = solver.hierarchy.tree.leaf_of_element[e];
        const cluster_node& r = solver.hierarchy.tree.nodes[std::size_t(leaf)];
        const double weight = r.area * channel_max(solver.hierarchy.rho[e]) * receiver_weight(solver, leaf);
        if (!(weight > 0.0)) continue;
        auto lamp = [&](const vec3& p) {
          rgb e_at = punctual_light_irradiance(s, solver.context, p, r.normal, rays);
          if (!src.light_images.empty())
            e_at += mirrored_light_irradiance(solver.context, src.light_images, p, r.normal, rays);
          return channel_max(e_at);
        };
        double lo = lamp(r.centroid), hi = lo;
        for (const vec3& corner : element_corners(mesh, e)) {
          // Towards the corners, not at them: a corner may touch an occluder.
          const double at = lamp(r.centroid + 0.75 * (corner - r.centroid));
          lo = std::min(lo, at);
          hi = std::max(hi, at);
        }
        const double ratio = (hi - lo) * weight / tolerance;
        if (!(ratio > 1.0) || !(element_longest_edge(mesh, e) > element_min_edge(solver, e))) continue;
        parts[part].emplace_back(int(e), std::clamp(int(std::ceil(std::log2(ratio))), 1, solver.params.max_bisections));
      }
    cast += rays;
  });
  rays_cast += cast;
  std::vector<std::pair<int, int>> out;
  for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

bool splits_pending(const hierarchical_solver& solver) {
  return solver.params.split_elements && !solver.split_marks.empty() &&
         solver.progress.element_passes < solver.params.max_element_passes && solver.progress.warning.empty();
}

bool split_marked_elements(hierarchical_solver& solver) {
  if (solver.split_marks.empty()) return false;
  const std::size_t n = solver.mesh().element_count();
  BOUNCE_CHECK_EQ(solver.split_marks.size(), n);
  auto refined = std::make_shared<patch_mesh>(solver.mesh());
  std::vector<int> marked, times, from;  // from[e]: the element of the current mesh that element e lies in
  for (std::size_t e = 0; e < n; ++e)
    if (solver.split_marks[e] > 0) {
      marked.push_back(int(e));
      times.push_back(solver.split_marks[e]);
    }
  std::string error;
  // Each mark says how often (at most to its element's own minimum edge);
  // the mesher's floor is the lowest any element may reach.
  const bool follows = !solver.view.seen.empty() && solver.meshes.min_edge_follows_view;
  const double floor = follows ? solver.meshes.min_edge / 8.0 : solver.meshes.min_edge;
  bool split = refine_patch_mesh(*refined, marked, floor, from, error, times);
  if (!split) solver.progress.warning = "element refinement stopped: " + error;
  split = split && refined->element_count() > n;
  solver.split_marks.clear();
  ++solver.progress.element_passes;
  if (!split) return false;
  BOUNCE_CHECK_EQ(from.size(), refined->element_count());

  // The old tree continues with subtrees over the pieces, so the links
  // stay (renumbered); the next link refinement splits those that the
  // pieces now allow. Each piece keeps its element's radiosity: the
  // piecewise-constant solution is unchanged, and iterating goes on from it.
  link_hierarchy& h = solver.hierarchy;
  std::vector<int> node_of_old;
  cluster_tree tree = extend_cluster_tree(h.tree, *refined, from, node_of_old);
  link_table<hierarchy_link> links = std::move(h.links);
  link_table<mirror_link> mirror_links = std::move(h.mirror_links);
  renumber_links(links, node_of_old);
  renumber_links(mirror_links, node_of_old);
  const light_parts light = std::move(solver.light);
  solver.meshes.refined = refined;
  solver.meshes.current = refined.get();
  if (!solver.sources.specular_lamp.empty()) solver.sources.specular_lamp = carried(solver.sources.specular_lamp, from);
  solver.meshes.input_element = carried(solver.meshes.input_element, from);
  rebuild_for_mesh(solver, std::move(tree));
  h.links = std::move(links);
  h.mirror_links = std::move(mirror_links);
  index_links(h.links, h.tree.nodes.size());
  index_links(h.mirror_links, h.tree.nodes.size());
  solver.light.total = carried(light.total, from);
  solver.light.direct = carried(light.direct, from);
  solver.light.mirrored = carried(light.mirrored, from);
  solver.residual.assign(refined->element_count(), rgb(0.0));
  solver.gathered = {};
  solver.gathered_at.clear();
  return true;
}

}  // namespace bounce
