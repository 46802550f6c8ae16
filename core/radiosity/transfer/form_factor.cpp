#include "radiosity/transfer/form_factor.h"

#include "radiosity/transfer/hemicube.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>

#include "base/parallel.h"
#include "base/random_stream.h"
#include "radiosity/transfer/mirror_images.h"
#include "radiosity/transfer/occlusion.h"

namespace bounce {
namespace {

using std::numbers::pi;

// Polygon clipped to the half-space n . (x - p) >= 0 (Sutherland-Hodgman).
// `out` holds at least in.size() + 1 points (a convex cut adds at most one).
int clip_to_hemisphere(const vec3& p, const vec3& n, std::span<const vec3> in, vec3* out) {
  int count = 0;
  const std::size_t k = in.size();
  for (std::size_t i = 0; i < k; ++i) {
    const vec3& a = in[i];
    const vec3& b = in[(i + 1) % k];
    const double da = glm::dot(n, a - p), db = glm::dot(n, b - p);
    if (da >= 0.0) out[count++] = a;
    if ((da >= 0.0) != (db >= 0.0)) out[count++] = a + (b - a) * (da / (da - db));
  }
  return count;
}

// Lambert's sum over a polygon's edges (already clipped to the hemisphere).
double contour_integral(const vec3& p, const vec3& n, const vec3* polygon, int k) {
  double sum = 0.0;
  for (int i = 0; i < k; ++i) {
    const vec3 ai = polygon[i] - p, bi = polygon[(i + 1) % k] - p;
    const vec3 cross = glm::cross(ai, bi);
    const double length = glm::length(cross);
    if (!(length > 0.0)) continue;  // an edge through p's line of sight contributes nothing
    const double gamma = std::atan2(length, glm::dot(ai, bi));
    sum += gamma * glm::dot(n, cross) / length;
  }
  return std::abs(sum) / (2.0 * pi);
}

// Each (seed, vertex, element) pair has its own reproducible jitter
// (hash_chain), whatever the order of the shots.
using pair_random = hash_chain;

// Stratified points on a triangle: an m x m grid of jittered cells in the
// unit square, mapped to the triangle with the area-preserving sqrt warp.
void stratified_points(const vec3& a, const vec3& b, const vec3& c, int m, pair_random& random, std::span<vec3> out) {
  int i = 0;
  for (int y = 0; y < m; ++y)
    for (int x = 0; x < m; ++x) {
      const double u = (x + random.uniform()) / m, v = (y + random.uniform()) / m;
      const double su = std::sqrt(u);
      out[i++] = a * (1.0 - su) + b * (su * (1.0 - v)) + c * (su * v);
    }
}

struct raycast_query {
  const form_factor_context& context;
  int grid;                    // shadow rays per (sub-)shooter: grid x grid
  const mirror_path& through;  // a mirror image's mirrors (empty: a real shooter)

  // Fraction of `count` stratified rays from the receiver to the triangle
  // that are unblocked.
  int unblocked(const vec3& p, const vec3& n, const vec3& a, const vec3& b, const vec3& c, const vec3& shooter_normal,
                int m, pair_random& random, std::uint64_t& rays) const {
    std::array<vec3, 64> targets;
    const int count = m * m;
    stratified_points(a, b, c, m, random, std::span(targets.data(), count));
    // Targets are lifted off the shooter and pulled in from its edges by
    // the offset: a sample on an edge shared with a perpendicular wall
    // would otherwise graze that wall at float precision.
    const vec3 from = p + n * context.offset;
    const vec3 centroid = (a + b + c) / 3.0;
    for (int i = 0; i < count; ++i) {
      const vec3 inward = centroid - targets[i];
      const double length = glm::length(inward);
      const double pull = std::min(context.offset, 0.5 * length);
      targets[i] += shooter_normal * context.offset + (length > 0.0 ? inward * (pull / length) : vec3(0.0));
    }
    if (through.count > 0) {  // a mirror image: each ray bends at its mirrors
      int seen = 0;
      for (int i = 0; i < count; ++i) seen += visible_through_mirrors(context, through, from, targets[i]) ? 1 : 0;
      rays += std::uint64_t(count) * std::uint64_t(through.count + 1);
      return seen;
    }
    rays += count;
    return context.occlusion->count_unblocked(from, std::span(targets.data(), count));
  }

  // F from the receive point to triangle (a, b, c) with visibility; splits
  // the triangle where it is partly hidden and large for its distance.
  double evaluate(const vec3& p, const vec3& n, const vec3& a, const vec3& b, const vec3& c, const vec3& shooter_normal,
                  int depth, pair_random& random, std::uint64_t& rays) const {
    const vec3 triangle[3] = {a, b, c};
    const double unoccluded = point_polygon_form_factor(p, n, triangle);
    if (unoccluded <= 0.0) return 0.0;
    const vec3 centroid = (a + b + c) / 3.0;
    const double size = std::sqrt(0.5 * glm::length(glm::cross(b - a, c - a)));
    const bool large = size > context.params.subdivide_ratio * glm::length(centroid - p);
    // Spend rays where visibility is partial: a 2x2 probe decides a small
    // shooter that it sees wholly visible or wholly hidden.
    if (context.params.adaptive_rays && grid > 2 && !large) {
      const int probe = unblocked(p, n, a, b, c, shooter_normal, 2, random, rays);
      if (probe == 4) return unoccluded;
      if (probe == 0) return 0.0;
    }
    const int count = grid * grid;
    const int visible = unblocked(p, n, a, b, c, shooter_normal, grid, random, rays);
    if (visible == count) return unoccluded;
    if (depth < context.params.max_subdivision && large) {
      // Partly hidden and large for its distance: the hidden fraction of
      // the area is not the hidden fraction of the form factor. Split.
      const vec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
      return evaluate(p, n, a, ab, ca, shooter_normal, depth + 1, random, rays) +
             evaluate(p, n, ab, b, bc, shooter_normal, depth + 1, random, rays) +
             evaluate(p, n, ca, bc, c, shooter_normal, depth + 1, random, rays) +
             evaluate(p, n, ab, bc, ca, shooter_normal, depth + 1, random, rays);
    }
    return unoccluded * visible / count;
  }
};

// Ray-cast F(v, from) for the receivers (all vertices when empty), with
// each one's visibility class when `visibility` is not empty. out and
// visibility are indexed like the receivers.
std::uint64_t raycast_form_factors(const form_factor_context& context, const shooter& from,
                                   std::span<const int> receivers, std::span<double> out,
                                   std::span<std::uint8_t> visibility) {
  const patch_mesh& mesh = *context.mesh;
  const vec3 a = from.corners[0], b = from.corners[1], c = from.corners[2];
  const vec3 centroid = (a + b + c) / 3.0;
  const vec3 shooter_normal = from.normal;
  // Each shooter has its own jitter stream. When patches are the elements
  // their indices coincide, so both paths give identical form factors.
  std::uint64_t shooter_id = std::uint64_t(from.element >= 0 ? from.element : from.patch);
  for (int i = 0; i < from.through.count; ++i)
    shooter_id = mix64(shooter_id ^ std::uint64_t(from.through.mirrors[i] + 1));
  const int grid = std::clamp(int(std::ceil(std::sqrt(double(std::max(context.params.shadow_rays, 1))) - 1e-9)), 1, 8);
  const raycast_query query{context, grid, from.through};
  std::atomic<std::uint64_t> total_rays{0};
  // A receiver in the shooter's plane sees it edge-on: F = 0. That covers
  // the shooter's own vertices and its flat neighbours, which round-off
  // would otherwise put a hair in front with a large, wrong form factor.
  const double in_plane = 1e-9 * mesh.scene_diagonal;
  const vec3 triangle[3] = {a, b, c};
  auto receive = [&](std::size_t begin, std::size_t end) {
    std::uint64_t rays = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t v = receivers.empty() ? i : std::size_t(receivers[i]);
      const vec3& p = mesh.receive_points[v];
      // The shooter emits from its front only; a receiver behind (or in)
      // its plane gets nothing.
      if (glm::dot(shooter_normal, p - centroid) <= in_plane) {
        out[i] = 0.0;
        if (!visibility.empty()) visibility[i] = facing_away;
        continue;
      }
      pair_random random{mix64(context.params.seed ^ mix64(v * 0x100000001B3ull ^ shooter_id))};
      out[i] = query.evaluate(p, mesh.normals[v], a, b, c, shooter_normal, 0, random, rays);
      if (!visibility.empty()) {
        const double unoccluded = point_polygon_form_factor(p, mesh.normals[v], triangle);
        visibility[i] = unoccluded <= 0.0      ? facing_away
                        : out[i] == 0.0        ? hidden
                        : out[i] == unoccluded ? seen_whole
                                               : seen_partly;
      }
    }
    total_rays += rays;
  };
  for_each_block(context.params.parallel, receivers.empty() ? mesh.vertex_count() : receivers.size(), 64, receive);
  return total_rays;
}

}  // namespace

double point_polygon_form_factor(const vec3& p, const vec3& n, std::span<const vec3> polygon) {
  // Triangles and quads, the hot path, stay on the stack.
  std::array<vec3, 16> small;
  std::vector<vec3> large;
  vec3* clipped = small.data();
  if (polygon.size() + 1 > small.size()) {
    large.resize(polygon.size() + 1);
    clipped = large.data();
  }
  const int k = clip_to_hemisphere(p, n, polygon, clipped);
  return k < 3 ? 0.0 : contour_integral(p, n, clipped, k);
}

form_factor_context make_form_factor_context(const patch_mesh& mesh, const form_factor_params& params) {
  form_factor_context context;
  context.mesh = &mesh;
  context.params = params;
  context.occlusion = std::make_shared<occlusion_scene>(mesh.positions, mesh.elements);
  context.vertex_areas.assign(mesh.vertex_count(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) context.vertex_areas[mesh.elements[e][k]] += mesh.element_areas[e] / 3.0;
  // Shadow rays start and end lifted off their surfaces along the normal,
  // so they do not hit the surface they start on. Embree works in floats
  // (7 digits), so the lift must be far above float round-off at the
  // scene's scale yet far below any feature: 1e-5 of the diagonal (about
  // 200 float ulps; 0.01 mm in the Cornell box).
  context.offset = 1e-5 * mesh.scene_diagonal;
  return context;
}

namespace {

std::uint64_t shoot(const form_factor_context& context, const shooter& from, std::span<double> out) {
  if (context.params.method == form_factor_method::hemicube && from.through.count == 0)
    return hemicube_form_factors(context, from, out);
  return raycast_form_factors(context, from, {}, out, {});
}

}  // namespace

std::uint64_t form_factors_to_element(const form_factor_context& context, int element, std::span<double> out) {
  const patch_mesh& mesh = *context.mesh;
  shooter from;
  from.corners = element_corners(mesh, std::size_t(element));
  from.normal = mesh.element_normals[element];
  from.area = mesh.element_areas[element];
  from.element = element;
  return shoot(context, from, out);
}

shooter patch_shooter(const patch_mesh& mesh, int patch) {
  shooter from;
  from.corners = mesh.patch_corners[patch];
  from.normal = mesh.patch_normals[patch];
  from.area = mesh.patch_areas[patch];
  from.patch = patch;
  return from;
}

std::uint64_t form_factors_to_patch(const form_factor_context& context, int patch, std::span<double> out) {
  return shoot(context, patch_shooter(*context.mesh, patch), out);
}

std::uint64_t form_factors_by_rays(const form_factor_context& context, const shooter& from,
                                   std::span<const int> receivers, std::span<double> out,
                                   std::span<std::uint8_t> visibility) {
  return raycast_form_factors(context, from, receivers, out, visibility);
}

bool visible(const form_factor_context& context, const vec3& from, const vec3& from_normal, const vec3& to,
             const vec3& to_normal) {
  return !context.occlusion->occluded(from + from_normal * context.offset, to + to_normal * context.offset);
}

}  // namespace bounce
