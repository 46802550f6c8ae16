#include "radiosity/hierarchical/view_importance.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "base/parallel.h"
#include "optics/optics.h"
#include "radiosity/hierarchical/sources.h"
#include "radiosity/hierarchical/transport.h"
#include "radiosity/transfer/occlusion.h"
#include "scene/camera_math.h"

namespace bounce {
namespace {

// Sweeps of W = rho R + K W: importance that has bounced this many times
// is counted, the rest (rho^n of it) is not; the weights need a factor of
// two, not digits.
constexpr int importance_sweeps = 8;

// Follows one camera ray: each element it meets takes `weight`, and the
// ray goes on through mirrors (kr) and glass (kt, unbent: the weights need
// where the light goes roughly, not the image's exact place).
void follow_ray(const patch_mesh& mesh, const scene& s, const form_factor_context& context, vec3 from, vec3 direction,
                std::vector<std::pair<int, double>>& hits) {
  const double reach = 4.0 * mesh.scene_diagonal;
  double weight = 1.0;
  for (int bounce = 0; bounce < 5 && weight > 1e-3; ++bounce) {
    const occlusion_scene::crossing hit = context.occlusion->first_crossing(from, from + direction * reach);
    if (hit.triangle < 0) return;
    const std::size_t e = std::size_t(hit.triangle);
    hits.emplace_back(hit.triangle, weight);
    const material& m = s.materials[std::size_t(mesh.element_materials[e])];
    const double kr = channel_max(m.kr), kt = channel_max(m.kt);
    if (!(kr > 0.0) && !(kt > 0.0)) return;
    const vec3 point = from + direction * (reach * hit.t);
    const vec3& n = mesh.element_normals[e];
    if (kr >= kt) {
      direction = reflect(direction, n);
      weight *= kr;
    } else {
      weight *= kt;
    }
    from = point + direction * context.offset;
  }
}

}  // namespace

std::vector<double> seen_density(const patch_mesh& mesh, const scene& s, const form_factor_context& context,
                                 const camera& view, int rays_across, bool parallel) {
  const double aspect = double(std::max(view.width, 1)) / double(std::max(view.height, 1));
  const int columns = std::max(1, int(std::lround(rays_across * std::sqrt(aspect))));
  const int rows = std::max(1, int(std::lround(rays_across / std::sqrt(aspect))));
  const camera_rays rays(view);
  // Hits per row, summed in row order: the same weights whatever the threads.
  std::vector<std::vector<std::pair<int, double>>> row_hits(static_cast<std::size_t>(rows));
  for_each_block(parallel, std::size_t(rows), 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < columns; ++x) {
        const double px = (x + 0.5) * view.width / columns, py = (double(y) + 0.5) * view.height / rows;
        follow_ray(mesh, s, context, view.eye, rays.direction(px, py), row_hits[y]);
      }
  });
  std::vector<double> density(mesh.element_count(), 0.0);
  for (const auto& hits : row_hits)
    for (const auto& [e, weight] : hits) density[std::size_t(e)] += weight;
  for (std::size_t e = 0; e < density.size(); ++e)
    density[e] = mesh.element_areas[e] > 0.0 ? density[e] / mesh.element_areas[e] : 0.0;
  return density;
}

void set_view(hierarchical_solver& solver, const std::optional<camera>& view) {
  constexpr int rays_across = 256;
  solver.view.seen.clear();
  solver.view.rays_per_pixel = 0.0;
  if (view) {
    solver.view.seen =
        seen_density(*solver.meshes.input, *solver.source, solver.context, *view, rays_across, solver.params.parallel);
    solver.view.rays_per_pixel =
        rays_across / std::sqrt(double(std::max(view->width, 1)) * double(std::max(view->height, 1)));
  }
  solver.view.node.clear();
  solver.view.retarget = true;
}

void update_view_weights(hierarchical_solver& solver) {
  solver.view.node.clear();
  if (solver.view.seen.empty() || solver.hierarchy.links.empty()) return;
  const std::size_t n = solver.mesh().element_count();
  const link_hierarchy& h = solver.hierarchy;
  std::vector<rgb> seen(n), sent(n), gathered(n), mirrored(n);
  for (std::size_t e = 0; e < n; ++e) seen[e] = rgb(solver.view.seen[std::size_t(solver.meshes.input_element[e])]);
  // Y = R + the importance gathered from W; W = rho Y.
  std::vector<rgb> passed_on = seen;
  for (int sweep = 0; sweep < importance_sweeps; ++sweep) {
    for (std::size_t e = 0; e < n; ++e) sent[e] = h.rho[e] * passed_on[e];
    gather_push(solver, sent, gathered, &mirrored);
    ++solver.progress.operator_applications;
    for (std::size_t e = 0; e < n; ++e) passed_on[e] = seen[e] + gathered[e] * h.normalizer[e].rest + mirrored[e];
  }
  // Scaled so that a scene seen evenly weighs 1: the power leaving all
  // surfaces over what it brings the picture through all bounces,
  // sum A (Y B - R E) (emitters seen straight are no link's business). A
  // view of one room of a building then weighs that room by the building's
  // power over the room's. No light in the picture: no lead.
  const std::vector<rgb>& b = solver.light.total;
  double power = 0.0, picture = 0.0;
  for (std::size_t e = 0; e < n; ++e) {
    const double area = solver.mesh().element_areas[e];
    power += area * channel_sum(b[e]);
    picture += area * channel_sum(passed_on[e] * b[e] - seen[e] * solver.sources.emission[e]);
  }
  if (!(picture > 0.0) || !(power > 0.0)) return;
  std::vector<rgb> node_y(solver.hierarchy.tree.nodes.size());
  pull(solver, passed_on, node_y, nullptr);
  const double scale = power / picture;
  solver.view.node.resize(node_y.size());
  for (std::size_t i = 0; i < node_y.size(); ++i) solver.view.node[i] = channel_max(node_y[i]) * scale;
}

}  // namespace bounce
