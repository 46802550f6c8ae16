#include "radiosity/hierarchical/oracle.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include "base/random_stream.h"
#include "radiosity/hierarchical/node_kernels.h"
#include "radiosity/hierarchical/view_importance.h"
#include "radiosity/transfer/mirror_images.h"
#include "radiosity/transfer/occlusion.h"

namespace bounce {
namespace {

// Whether every point of box [lo, hi] lies at or behind the plane of
// normal n through the nearest point of `other` (other_lo..other_hi) along n.
bool behind(const vec3& n, const vec3& lo, const vec3& hi, const vec3& other_lo, const vec3& other_hi, double slack) {
  double front = 0.0, back = 0.0;
  for (int k = 0; k < 3; ++k) {
    front += n[k] * (n[k] >= 0.0 ? hi[k] : lo[k]);             // the box's farthest point along n
    back += n[k] * (n[k] >= 0.0 ? other_lo[k] : other_hi[k]);  // the other's lowest point along n
  }
  return front <= back + slack;
}

// Overlapping bounds: the estimate says nothing; charge the largest
// factor. The centroids' cosines can be near 0 where parts of the two
// still face each other: charge at least a tenth of the factor without them.
double bound_of(const cluster_node& r, const cluster_node& s, double factor, double r2) {
  const bool close = std::sqrt(r2) < r.radius() + s.radius();
  return close ? 1.0 : std::max(factor, 0.1 * s.area / (std::numbers::pi * r2 + s.area));
}

struct image_of_node {
  vec3 centroid, normal, lo, hi;
};

image_of_node node_image(const cluster_node& s, const mirror_chain& chain) {
  image_of_node out;
  out.centroid = chain.image(s.centroid);
  out.normal = chain.image_direction(s.normal);
  image_box(chain, s.lo, s.hi, out.lo, out.hi);
  return out;
}

}  // namespace

link_estimate estimate(const hierarchical_solver& solver, int i, int j) {
  const cluster_node& r = solver.hierarchy.tree.nodes[std::size_t(i)];
  const cluster_node& s = solver.hierarchy.tree.nodes[std::size_t(j)];
  const patch_mesh& mesh = solver.mesh();
  link_estimate e;
  const double slack = 1e-9 * mesh.scene_diagonal;
  if ((r.oriented && behind(r.normal, s.lo, s.hi, r.lo, r.hi, slack)) ||
      (s.oriented && behind(s.normal, r.lo, r.hi, s.lo, s.hi, slack))) {
    e.none = true;
    return e;
  }
  if (r.leaf() && s.leaf()) {
    e.factor = e.bound = point_polygon_form_factor(r.centroid, r.normal, element_corners(mesh, std::size_t(s.element)));
    e.none = !(e.factor > 0.0);
    return e;
  }
  e.factor = disc_factor(s, r.centroid, r.oriented ? &r.normal : nullptr);
  const double r2 = glm::dot(s.centroid - r.centroid, s.centroid - r.centroid);
  e.bound = bound_of(r, s, e.factor, r2);
  return e;
}

link_estimate estimate_through(const hierarchical_solver& solver, int i, int j, const mirror_chain& chain) {
  const cluster_node& r = solver.hierarchy.tree.nodes[std::size_t(i)];
  const cluster_node& s = solver.hierarchy.tree.nodes[std::size_t(j)];
  const mirror_set& mirrors = *solver.context.mirrors;
  const planar_mirror& last = mirrors.mirrors[std::size_t(chain.path.mirrors[std::size_t(chain.path.count - 1)])];
  link_estimate e;
  e.none = true;
  if (!box_reaches_in_front(last, s.lo, s.hi, mirrors.tolerance)) return e;
  const image_of_node image = node_image(s, chain);
  const double slack = 1e-9 * solver.mesh().scene_diagonal;
  if ((r.oriented && behind(r.normal, image.lo, image.hi, r.lo, r.hi, slack)) ||
      (s.oriented && behind(image.normal, r.lo, r.hi, image.lo, image.hi, slack)) ||
      !may_cross_first_mirror(mirrors, chain, r.lo, r.hi, image.lo, image.hi))
    return e;
  e.none = false;
  const vec3 d = image.centroid - r.centroid;
  const double r2 = glm::dot(d, d);
  if (r.leaf() && s.leaf()) {
    std::array<vec3, 3> polygon = element_corners(solver.mesh(), std::size_t(s.element));
    for (vec3& corner : polygon) corner = chain.image(corner);
    e.factor = e.bound = point_polygon_form_factor(r.centroid, r.normal, polygon);
    e.none = !(e.factor > 0.0);
    return e;
  }
  e.factor = disc_factor(s, r.centroid, r.oriented ? &r.normal : nullptr, &chain);
  e.bound = bound_of(r, s, e.factor, r2);
  return e;
}

pair_charge charge(const hierarchical_solver& solver, const std::vector<rgb>& node_b, int i, int j,
                   const link_estimate& e) {
  const cluster_node& r = solver.hierarchy.tree.nodes[std::size_t(i)];
  const cluster_node& s = solver.hierarchy.tree.nodes[std::size_t(j)];
  pair_charge out;
  const double transfer = r.area * channel_max(node_b[std::size_t(j)]) * receiver_weight(solver, i);
  out.bf = out.split = e.bound * transfer;
  if (r.leaf() && s.leaf()) return out;
  const bool receiver = !r.leaf() && (s.leaf() || r.area >= s.area);  // as a split would choose
  if (!(receiver ? r : s).piece) return out;
  out.split = receiver && out.bf > 0.0 ? factor_variation(solver.hierarchy.tree, solver.mesh(), i, j) * transfer : 0.0;
  return out;
}

pair_charge charge_through(const hierarchical_solver& solver, const std::vector<rgb>& node_b, int i, int j, int c,
                           const link_estimate& e) {
  const cluster_tree& tree = solver.hierarchy.tree;
  const patch_mesh& mesh = solver.mesh();
  const cluster_node& r = tree.nodes[std::size_t(i)];
  const cluster_node& s = tree.nodes[std::size_t(j)];
  const mirror_chain& chain = solver.hierarchy.chains[std::size_t(c)];
  const double transfer =
      channel_max(chain.path.kr) * r.area * channel_max(node_b[std::size_t(j)]) * receiver_weight(solver, i);
  double bound = e.bound;
  if (!s.leaf()) {
    double lo = INFINITY, hi = 0.0;
    for (const int element : tree.strata[std::size_t(j)]) {
      const vec3 q = chain.image(element_centroid(mesh, std::size_t(element)));
      const vec3 n = chain.image_direction(mesh.element_normals[std::size_t(element)]);
      const vec3 d = q - r.centroid;
      const double d2 = glm::dot(d, d);
      if (!(d2 > 0.0)) continue;
      const double receive = r.oriented ? std::max(0.0, glm::dot(r.normal, d)) : std::sqrt(d2);
      const double kernel = receive * std::max(0.0, -glm::dot(n, d)) / (std::numbers::pi * d2 * d2);
      lo = std::min(lo, kernel);
      hi = std::max(hi, kernel);
    }
    if (hi > lo) bound = std::max(bound, (hi - lo) * s.area);
  }
  pair_charge out;
  out.bf = out.split = bound * transfer;
  return out;
}

namespace {

// The visible fraction of a set of shadow rays, each weighted by what it
// would carry; by count where none carries anything.
struct visible_fraction {
  double open = 0.0, total = 0.0;
  int open_rays = 0, rays = 0;

  void add(double weight, bool passes) {
    open_rays += passes ? 1 : 0;
    ++rays;
    total += weight;
    open += passes ? weight : 0.0;
  }
  float value() const {
    if (total > 0.0) return float(open / total);
    return rays > 0 ? float(open_rays) / float(rays) : 0.0f;
  }
};

}  // namespace

float pair_visibility(const hierarchical_solver& solver, int i, int j, int count, int c,
                      std::atomic<std::uint64_t>& rays) {
  const mirror_chain* chain = c >= 0 ? &solver.hierarchy.chains[std::size_t(c)] : nullptr;
  const cluster_tree& tree = solver.hierarchy.tree;
  const cluster_node& r = tree.nodes[std::size_t(i)];
  const cluster_node& s = tree.nodes[std::size_t(j)];
  // Leaves are keyed by element, so that the element-level solution casts the same rays.
  const std::uint64_t key_i = r.leaf() ? std::uint64_t(r.element) : (1ull << 40) + std::uint64_t(i);
  const std::uint64_t key_j = s.leaf() ? std::uint64_t(s.element) : (1ull << 40) + std::uint64_t(j);
  const std::uint64_t key = chain ? key_j ^ mix64(std::uint64_t(c)) : key_j;
  hash_chain random{mix64(solver.params.seed ^ mix64(key_i * 0x100000001b3ull ^ mix64(key)))};
  // Each pair counts by what it would carry (the cosines at both ends):
  // pairs that face away from each other carry nothing, and would
  // otherwise count the back of a box as a shadow.
  visible_fraction fraction;
  for (int k = 0; k < count; ++k) {
    // Stratified along the first coordinate of both ends.
    const double u1 = (k + random.uniform()) / count, v1 = random.uniform();
    const double u2 = (((k * 7 + 3) % count) + random.uniform()) / count, v2 = random.uniform();
    const surface_point p = sample_node(tree, solver.mesh(), i, u1, v1);
    surface_point q = sample_node(tree, solver.mesh(), j, u2, v2);
    if (chain) q = {chain->image(q.position), chain->image_direction(q.normal)};
    const vec3 pq = q.position - p.position;
    const double offset = solver.context.offset;
    const vec3 from = p.position + p.normal * (glm::dot(pq, p.normal) >= 0.0 ? offset : -offset);
    const vec3 to = q.position + q.normal * (glm::dot(pq, q.normal) <= 0.0 ? offset : -offset);
    const double length = glm::length(pq);
    const double weight = length > 0.0 ? std::max(0.0, glm::dot(pq, p.normal)) *
                                             std::max(0.0, -glm::dot(pq, q.normal)) / (length * length)
                                       : 0.0;
    fraction.add(weight, chain ? weight > 0.0 && visible_through_mirrors(solver.context, chain->path, from, to)
                               : !solver.context.occlusion->occluded(from, to));
  }
  rays += std::uint64_t(count);
  return fraction.value();
}

float point_visibility(const hierarchical_solver& solver, const vec3& p, const vec3& n, int j, int count,
                       std::uint64_t& rays) {
  const cluster_tree& tree = solver.hierarchy.tree;
  std::uint64_t key = mix64(std::uint64_t(j));
  for (double c : {p.x, p.y, p.z}) key = mix64(key ^ std::bit_cast<std::uint64_t>(c));
  hash_chain random{mix64(solver.params.seed ^ key)};
  const double offset = solver.context.offset;
  const int side = std::max(1, int(std::sqrt(double(count))));
  visible_fraction fraction;
  for (int k = 0; k < count; ++k) {
    // Jittered on a side x side grid over the source's (u, v): a shadow
    // edge crossing the source is found with far less noise than by
    // independent samples.
    const int row = k / side, column = k % side;
    const double u = row < side ? (column + random.uniform()) / side : random.uniform();
    const double w = row < side ? (row + random.uniform()) / side : random.uniform();
    const surface_point q = sample_node(tree, solver.mesh(), j, u, w);
    const vec3 pq = q.position - p;
    const double length = glm::length(pq);
    const double weight = length > 0.0 ? std::max(0.0, glm::dot(pq, n)) * std::max(0.0, -glm::dot(pq, q.normal)) /
                                             (length * length * length * length)
                                       : 0.0;
    const vec3 from = p + n * offset;
    const vec3 to = q.position + q.normal * (glm::dot(pq, q.normal) <= 0.0 ? offset : -offset);
    fraction.add(weight, !solver.context.occlusion->occluded(from, to));
  }
  rays += std::uint64_t(count);
  return fraction.value();
}

double kept_factor(const hierarchical_solver& solver, int i, int j, const link_estimate& e, bool source_emits) {
  const cluster_node& r = solver.hierarchy.tree.nodes[std::size_t(i)];
  const cluster_node& s = solver.hierarchy.tree.nodes[std::size_t(j)];
  if (s.leaf() || !r.oriented || (solver.progress.closed && !source_emits)) return e.factor;
  return strata_factor(solver.hierarchy.tree, solver.mesh(), j, r.centroid, r.normal);
}

}  // namespace bounce
