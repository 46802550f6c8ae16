#include "radiosity/hierarchical.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>

#include "base/check.h"
#include "base/parallel.h"
#include "base/random_stream.h"
#include "mesh/patch_mesh.h"
#include "radiosity/transfer/occlusion.h"
#include "radiosity/transfer/point_lights.h"
#include "radiosity/transfer/specular_paths.h"

namespace bounce {
namespace {

// Irradiance on an oriented surface of normal n from six direction bins.
rgb from_bins(const std::array<rgb, 6>& bins, const vec3& n) {
  rgb sum(0.0);
  for (int k = 0; k < 3; ++k) sum += n[k] >= 0.0 ? n[k] * bins[2 * k] : -n[k] * bins[2 * k + 1];
  return sum;
}

// The disc estimate of the form factor from a point p to node s: a disc
// of s's projected area towards p, at its centroid, facing p: F = A /
// (pi r^2 + A), finite as r goes to 0. Times the cosine at p when the
// point has a normal n (a cluster receiver has none: per unit area facing
// the source). `towards` is set to the unit direction from p to s, and
// `send` to s's projected area towards p. Through a mirror chain, the
// same to s's image.
double disc_factor(const cluster_node& s, const vec3& p, const vec3* n, vec3& towards, double& send,
                   const mirror_chain* chain = nullptr) {
  const vec3 d = (chain ? chain->image(s.centroid) : s.centroid) - p;
  const double r2 = glm::dot(d, d);
  towards = r2 > 0.0 ? d / std::sqrt(r2) : vec3(0.0);
  const double receive = n ? std::max(0.0, glm::dot(*n, towards)) : 1.0;
  send = projected_area(s, chain ? chain->source_direction(-towards) : -towards);
  return std::min(1.0, receive * send / (std::numbers::pi * r2 + send));
}

double disc_factor(const cluster_node& s, const vec3& p, const vec3* n, const mirror_chain* chain = nullptr) {
  vec3 towards;
  double send = 0.0;
  return disc_factor(s, p, n, towards, send, chain);
}

// The form factor from a point p (normal n) to inner node s, from its
// sample_strata elements (drawn by area): each element's exact factor
// (Lambert's formula) stands for its share of the node's area. The disc
// estimate misses by the second order of the source's angular size, and
// in a box nearly always the same way: in a closed Cornell box at the
// default tolerance its sums of form factors came out 0.8-2.5% short per
// surface, and that much light was missing at every bounce; with this
// estimate they are within 0.2% of 1 on the walls and 1.1% on the blocks.
double strata_factor(const cluster_tree& tree, const patch_mesh& mesh, int s, const vec3& p, const vec3& n) {
  constexpr int strata = cluster_tree::sample_strata;
  const double share = tree.nodes[std::size_t(s)].area / strata;
  double sum = 0.0;
  for (const int element : tree.strata[std::size_t(s)]) {
    const glm::ivec3 t = mesh.elements[std::size_t(element)];
    const vec3 polygon[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
    const vec3& normal = mesh.element_normals[std::size_t(element)];
    if (glm::dot(normal, p - polygon[0]) <= 0.0) continue;  // faces away
    const double area = mesh.element_areas[std::size_t(element)];
    const vec3 d = (polygon[0] + polygon[1] + polygon[2]) / 3.0 - p;
    const double r2 = glm::dot(d, d);
    if (area < 0.01 * std::numbers::pi * r2) {
      // Small as seen from p: the point-to-point kernel at its centre is
      // Lambert's formula to well under 1%, at a tenth of the cost.
      const double cosines = std::max(0.0, glm::dot(n, d)) * std::max(0.0, -glm::dot(normal, d)) / r2;
      sum += cosines / (std::numbers::pi * r2) * share;
    } else {
      sum += point_polygon_form_factor(p, n, polygon) * share / area;
    }
  }
  return std::min(1.0, sum);
}

// Pull: element radiosities up the tree as area-weighted means, level by
// level; and for clusters, what their elements send towards each of the
// six axis directions (sum of B x area x max(0, +-n_k)), the radiosity
// counterpart of cluster_node::projected (when `sent` is given).
void pull(const hierarchical_solver& solver, const std::vector<rgb>& x, std::vector<rgb>& node_b,
          std::vector<std::array<rgb, 6>>* sent) {
  const cluster_tree& tree = solver.tree;
  if (sent) sent->resize(solver.buffers.bins.size());
  for (int level = int(tree.levels.size()) - 2; level >= 0; --level) {
    const std::size_t begin = std::size_t(tree.levels[level]), end = std::size_t(tree.levels[level + 1]);
    for_each_block(solver.params.parallel, end - begin, 4096, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = begin + b; i < begin + e; ++i) {
        const cluster_node& node = tree.nodes[i];
        if (node.leaf()) {
          node_b[i] = x[node.element];
          continue;
        }
        rgb sum(0.0);
        for (int c = node.first_child; c < node.first_child + node.child_count; ++c)
          sum += node_b[c] * tree.nodes[c].area;
        node_b[i] = node.area > 0.0 ? sum / node.area : rgb(0.0);
        const int slot = solver.cube_slot[i];
        if (!sent || slot < 0) continue;
        std::array<rgb, 6> out{};
        for (int c = node.first_child; c < node.first_child + node.child_count; ++c) {
          const cluster_node& child = tree.nodes[c];
          if (const int child_slot = solver.cube_slot[c]; child_slot >= 0) {
            for (int k = 0; k < 6; ++k) out[k] += (*sent)[child_slot][k];
          } else {
            for (int k = 0; k < 3; ++k)
              out[2 * k + (child.normal[k] >= 0.0 ? 0 : 1)] += node_b[c] * (child.area * std::abs(child.normal[k]));
          }
        }
        (*sent)[slot] = out;
      }
    });
  }
}

// The radiosity a source node sends towards unit direction d. A cluster's
// elements face many ways, and a receiver sees those that face it: the
// floor and a table top from above, the table's dark underside from
// below. Its area-weighted mean radiosity, which counts them all alike,
// made every cluster link carry the wrong mix, and in a room lit from
// above the ceiling came out 9% dark at the default tolerance.
// `area` is the source's projected area along d (projected_area).
rgb sent_radiosity(const hierarchical_solver& solver, const std::vector<rgb>& node_b,
                   const std::vector<std::array<rgb, 6>>& sent, int source, const vec3& d, double area) {
  const int slot = solver.cube_slot[std::size_t(source)];
  if (slot < 0 || !(area > 0.0)) return node_b[std::size_t(source)];
  rgb sum(0.0);
  for (int k = 0; k < 3; ++k) sum += std::abs(d[k]) * sent[std::size_t(slot)][2 * k + (d[k] >= 0.0 ? 0 : 1)];
  return sum / area;
}

rgb sent_radiosity(const hierarchical_solver& solver, const std::vector<rgb>& node_b,
                   const std::vector<std::array<rgb, 6>>& sent, int source, const vec3& d) {
  if (solver.cube_slot[std::size_t(source)] < 0) return node_b[std::size_t(source)];
  return sent_radiosity(solver, node_b, sent, source, d, projected_area(solver.tree.nodes[std::size_t(source)], d));
}

// What one link brings its receiver: the source's radiosity towards the
// receiver (or its image's, through a mirror chain) times the factor and
// visibility, and the unit direction from the receiver to the source (or
// image), for cluster receivers' bins. False: no direction.
bool link_value(const hierarchical_solver& solver, const cluster_node& node, const hierarchy_link& link,
                const mirror_chain* chain, rgb& value, vec3& d) {
  const hierarchical_solver::transport_buffers& buf = solver.buffers;
  const cluster_node& source = solver.tree.nodes[std::size_t(link.source)];
  const vec3 at = chain ? chain->image(source.centroid) : source.centroid;
  const vec3 towards = at - node.centroid;
  const double length = glm::length(towards);
  if (!(length > 0.0)) return false;  // no direction (and its estimate is 0)
  d = towards / length;
  const vec3 out = chain ? chain->source_direction(-d) : -d;
  value =
      double(link.factor) * double(link.visibility) * sent_radiosity(solver, buf.node_b, buf.sent, link.source, out);
  if (chain) value *= chain->path.kr;
  return true;
}

// Gather over one set of links (plain, or through mirrors) into their
// receivers, then push the irradiance down to the elements: out[e] =
// irradiance on element e. The pull is made beforehand.
template <typename link_of>
void gather_links(const hierarchical_solver& solver, const std::vector<std::size_t>& offsets, link_of&& at,
                  std::vector<rgb>& out) {
  const cluster_tree& tree = solver.tree;
  hierarchical_solver::transport_buffers& buf = solver.buffers;
  const std::size_t n = tree.nodes.size();
  for_each_block(solver.params.parallel, n, 1024, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const cluster_node& node = tree.nodes[i];
      const int slot = solver.cube_slot[i];
      rgb sum(0.0);
      std::array<rgb, 6> bins{};
      for (std::size_t l = offsets[i]; l < offsets[i + 1]; ++l) {
        const mirror_chain* chain = nullptr;
        const hierarchy_link& link = at(l, chain);
        if (!chain && slot < 0 && solver.cube_slot[link.source] < 0) {
          sum += double(link.factor) * double(link.visibility) * buf.node_b[link.source];
          continue;
        }
        rgb value;
        vec3 d;
        if (!link_value(solver, node, link, chain, value, d)) continue;
        if (slot < 0) {
          sum += value;
          continue;
        }
        for (int k = 0; k < 3; ++k) bins[2 * k + (d[k] >= 0.0 ? 0 : 1)] += std::abs(d[k]) * value;
      }
      if (slot < 0)
        buf.gathered[i] = sum;
      else
        buf.bins[slot] = bins;
    }
  });
  // Push, level by level: a cluster's bins accumulate down to the first
  // oriented node, which turns them into irradiance on its normal.
  for (std::size_t level = 1; level + 1 < tree.levels.size(); ++level) {
    const std::size_t begin = std::size_t(tree.levels[level]), end = std::size_t(tree.levels[level + 1]);
    for_each_block(solver.params.parallel, end - begin, 4096, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = begin + b; i < begin + e; ++i) {
        const int parent = tree.nodes[i].parent;
        const int slot = solver.cube_slot[i], parent_slot = solver.cube_slot[parent];
        if (slot >= 0) {
          for (int k = 0; k < 6; ++k) buf.bins[slot][k] += buf.bins[parent_slot][k];
        } else {
          buf.gathered[i] +=
              parent_slot >= 0 ? from_bins(buf.bins[parent_slot], tree.nodes[i].normal) : buf.gathered[parent];
        }
      }
    });
  }
  out.resize(solver.mesh->element_count());
  for_each_block(solver.params.parallel, out.size(), 4096, [&](std::size_t b, std::size_t e) {
    for (std::size_t el = b; el < e; ++el) out[el] = buf.gathered[tree.leaf_of_element[el]];
  });
  // A single-element mesh: the root is the leaf, and oriented.
}

// Gather and push over the links: out[e] = irradiance on element e from
// the plain links, and, when `mirrored` is given, mirrored[e] from the
// links through mirrors (the form-factor normaliser applies to the first
// alone: a mirror's solid angle is counted once, by the plain links to it).
void gather_push(const hierarchical_solver& solver, const std::vector<rgb>& x, std::vector<rgb>& out,
                 std::vector<rgb>* mirrored = nullptr) {
  hierarchical_solver::transport_buffers& buf = solver.buffers;
  pull(solver, x, buf.node_b, &buf.sent);
  gather_links(
      solver, solver.link_offsets,
      [&](std::size_t l, const mirror_chain*&) -> const hierarchy_link& { return solver.links[l]; }, out);
  if (!mirrored) return;
  if (solver.mirror_links.empty()) {
    mirrored->assign(out.size(), rgb(0.0));
    return;
  }
  gather_links(
      solver, solver.mirror_link_offsets,
      [&](std::size_t l, const mirror_chain*& chain) -> const hierarchy_link& {
        const mirror_link& m = solver.mirror_links[l];
        chain = &solver.chains[std::size_t(m.chain)];
        return m.link;
      },
      *mirrored);
}

// ---- link refinement ----

struct link_estimate {
  double factor = 0.0;  // what the link would carry per unit source radiosity
  double bound = 0.0;   // the form factor the oracle charges it with
  bool none = false;    // the two cannot exchange light (they face away)
};

// Whether every point of box [lo, hi] lies at or behind the plane of
// normal n through the nearest point of `other` (lo2..hi2) along n.
bool behind(const vec3& n, const vec3& lo, const vec3& hi, const vec3& other_lo, const vec3& other_hi, double slack) {
  double front = 0.0, back = 0.0;
  for (int k = 0; k < 3; ++k) {
    front += n[k] * (n[k] >= 0.0 ? hi[k] : lo[k]);             // the box's farthest point along n
    back += n[k] * (n[k] >= 0.0 ? other_lo[k] : other_hi[k]);  // the other's lowest point along n
  }
  return front <= back + slack;
}

struct refine_context {
  const hierarchical_solver& solver;
  const std::vector<rgb>& node_b;
  double tolerance;  // absolute: power units
  tbb::enumerable_thread_specific<std::vector<hierarchy_link>>& out;
  std::atomic<std::size_t>& count;
  std::atomic<std::uint64_t>& rays;
  std::atomic<bool>& limit_hit;
  tbb::enumerable_thread_specific<std::vector<std::pair<int, int>>>& marks;  // (element, bisections)
  tbb::enumerable_thread_specific<std::vector<mirror_link>>* mirror_out = nullptr;
};

double longest_edge(const patch_mesh& mesh, int element) {
  const glm::ivec3 t = mesh.elements[element];
  double longest = 0.0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, glm::length(mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]));
  return longest;
}

// An element-to-element pair that the tree cannot refine further: its
// receiving element is marked for bisection where the light it gets from
// the source changes across it. Evenly lit elements stay whole however
// much light they get: the error of a constant per element is the
// variation of the transfer (the form factor at its corners against the
// centre, times the source's radiosity and the element's area), or, on a
// shadow edge (partly visible), the whole transfer. The bisections asked
// for halve that error enough (each halves the area, and the variation
// with it). Through a mirror chain, the same with the source's image and kr.
void mark_split(refine_context& ctx, int i, int j, double factor, float visibility,
                const mirror_chain* chain = nullptr) {
  const hierarchical_solver& solver = ctx.solver;
  if (!solver.params.split_elements) return;
  const cluster_node& r = solver.tree.nodes[i];
  const cluster_node& s = solver.tree.nodes[j];
  const patch_mesh& mesh = *solver.mesh;
  const double transfer = r.area * channel_max(ctx.node_b[j]) * (chain ? channel_max(chain->path.kr) : 1.0);
  if (!(factor * transfer > ctx.tolerance)) return;  // nothing this pair carries can matter
  double error = 0.0;
  if (visibility > 0.0f && visibility < 1.0f) {
    error = solver.params.partial_factor * factor * transfer;
  } else if (visibility > 0.0f) {
    const glm::ivec3 st = mesh.elements[s.element];
    vec3 polygon[3] = {mesh.positions[st[0]], mesh.positions[st[1]], mesh.positions[st[2]]};
    if (chain)
      for (vec3& x : polygon) x = chain->image(x);
    const glm::ivec3 rt = mesh.elements[r.element];
    double lo = factor, hi = factor;
    for (int k = 0; k < 3; ++k) {
      // Towards the corners, not at them: a corner may touch the source.
      const vec3 p = r.centroid + 0.75 * (mesh.positions[rt[k]] - r.centroid);
      const double f = point_polygon_form_factor(p, r.normal, polygon);
      if (std::isfinite(f)) {
        lo = std::min(lo, f);
        hi = std::max(hi, f);
      }
    }
    error = (hi - lo) * transfer;
  }
  const double ratio = error / ctx.tolerance;
  if (!(ratio > 1.0) || !(longest_edge(mesh, r.element) > solver.min_edge)) return;
  const int bisections = std::clamp(int(std::ceil(std::log2(ratio))), 1, solver.params.max_bisections);
  ctx.marks.local().emplace_back(r.element, bisections);
}

link_estimate estimate(const hierarchical_solver& solver, int i, int j) {
  const cluster_node& r = solver.tree.nodes[i];
  const cluster_node& s = solver.tree.nodes[j];
  const patch_mesh& mesh = *solver.mesh;
  link_estimate e;
  const double slack = 1e-9 * mesh.scene_diagonal;
  if ((r.oriented && behind(r.normal, s.lo, s.hi, r.lo, r.hi, slack)) ||
      (s.oriented && behind(s.normal, r.lo, r.hi, s.lo, s.hi, slack))) {
    e.none = true;
    return e;
  }
  if (r.leaf() && s.leaf()) {
    const glm::ivec3 t = mesh.elements[s.element];
    const vec3 polygon[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
    e.factor = e.bound = point_polygon_form_factor(r.centroid, r.normal, polygon);
    e.none = !(e.factor > 0.0);
    return e;
  }
  e.factor = disc_factor(s, r.centroid, r.oriented ? &r.normal : nullptr);
  const double r2 = glm::dot(s.centroid - r.centroid, s.centroid - r.centroid);
  const double distance = std::sqrt(r2);
  // Overlapping bounds: the estimate says nothing; charge the largest
  // factor. The centroids' cosines can be near 0 where parts of the two
  // still face each other: charge at least a tenth of the factor without them.
  const bool close = distance < r.radius() + s.radius();
  e.bound = close ? 1.0 : std::max(e.factor, 0.1 * s.area / (std::numbers::pi * r2 + s.area));
  return e;
}

// The visible fraction of a pair from `count` shadow rays between sample
// points of both (through mirror chain `c`, to the source's image, when c
// >= 0: the rays must then pass the chain's mirrors).
float visibility(refine_context& ctx, int i, int j, int count, int c = -1) {
  const hierarchical_solver& solver = ctx.solver;
  const mirror_chain* chain = c >= 0 ? &solver.chains[std::size_t(c)] : nullptr;
  const cluster_node& r = solver.tree.nodes[i];
  const cluster_node& s = solver.tree.nodes[j];
  // Leaves are keyed by element, so that the element-level solution casts the same rays.
  const std::uint64_t key_i = r.leaf() ? std::uint64_t(r.element) : (1ull << 40) + std::uint64_t(i);
  const std::uint64_t key_j = s.leaf() ? std::uint64_t(s.element) : (1ull << 40) + std::uint64_t(j);
  const std::uint64_t key = chain ? key_j ^ mix64(std::uint64_t(c)) : key_j;
  hash_chain random{mix64(solver.params.seed ^ mix64(key_i * 0x100000001b3ull ^ mix64(key)))};
  // Each pair counts by what it would carry (the cosines at both ends):
  // pairs that face away from each other carry nothing, and would
  // otherwise count the back of a box as a shadow.
  double open = 0.0, total = 0.0;
  int open_rays = 0;
  for (int k = 0; k < count; ++k) {
    // Stratified along the first coordinate of both ends.
    const double u1 = (k + random.uniform()) / count, v1 = random.uniform();
    const double u2 = (((k * 7 + 3) % count) + random.uniform()) / count, v2 = random.uniform();
    const surface_point p = sample_node(solver.tree, *solver.mesh, i, u1, v1);
    surface_point q = sample_node(solver.tree, *solver.mesh, j, u2, v2);
    if (chain) q = {chain->image(q.position), chain->image_direction(q.normal)};
    const vec3 pq = q.position - p.position;
    const vec3 from =
        p.position + p.normal * (glm::dot(pq, p.normal) >= 0.0 ? solver.context.offset : -solver.context.offset);
    const vec3 to =
        q.position + q.normal * (glm::dot(pq, q.normal) <= 0.0 ? solver.context.offset : -solver.context.offset);
    const double length = glm::length(pq);
    const double weight = length > 0.0 ? std::max(0.0, glm::dot(pq, p.normal)) *
                                             std::max(0.0, -glm::dot(pq, q.normal)) / (length * length)
                                       : 0.0;
    const bool passes = chain ? weight > 0.0 && visible_through_mirrors(solver.context, chain->path, from, to)
                              : !solver.context.occlusion->occluded(from, to);
    open_rays += passes ? 1 : 0;
    total += weight;
    open += passes ? weight : 0.0;
  }
  ctx.rays += std::uint64_t(count);
  if (total > 0.0) return float(open / total);
  return float(open_rays) / float(count);
}

// What the oracle charges a pair. `bf` is BF refinement's F x B x A; it
// decides, except where the side a split would divide is a piece of an
// element split while solving (cluster_node::piece): pieces exist for how
// light varies over them, so a piece receiver is charged the variation of
// the form factor over its sample points times B x A, and a piece source
// is not divided for the light it carries (its pieces send their mean).
// Partly visible pairs are split on `bf` everywhere: shadows need pieces.
struct pair_error {
  double bf = 0.0;
  double split = 0.0;
};

double factor_variation(const hierarchical_solver& solver, int i, int j) {
  const cluster_tree& tree = solver.tree;
  const cluster_node& r = tree.nodes[std::size_t(i)];
  const cluster_node& s = tree.nodes[std::size_t(j)];
  const patch_mesh& mesh = *solver.mesh;
  vec3 polygon[3];
  if (s.leaf()) {
    const glm::ivec3 t = mesh.elements[std::size_t(s.element)];
    polygon[0] = mesh.positions[t[0]];
    polygon[1] = mesh.positions[t[1]];
    polygon[2] = mesh.positions[t[2]];
  }
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
  for (int element : tree.strata[std::size_t(i)]) {
    const glm::ivec3 t = mesh.elements[std::size_t(element)];
    add((mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0);
  }
  return hi > lo ? hi - lo : 0.0;
}

pair_error charge(const hierarchical_solver& solver, const std::vector<rgb>& node_b, int i, int j,
                  const link_estimate& e) {
  const cluster_node& r = solver.tree.nodes[std::size_t(i)];
  const cluster_node& s = solver.tree.nodes[std::size_t(j)];
  pair_error out;
  const double transfer = r.area * channel_max(node_b[std::size_t(j)]);
  out.bf = out.split = e.bound * transfer;
  if (r.leaf() && s.leaf()) return out;
  const bool receiver = !r.leaf() && (s.leaf() || r.area >= s.area);  // as split_pair chooses
  if (!(receiver ? r : s).piece) return out;
  out.split = receiver && out.bf > 0.0 ? factor_variation(solver, i, j) * transfer : 0.0;
  return out;
}

void refine_pair(refine_context& ctx, int i, int j);
void refine_pair_through(refine_context& ctx, int i, int j, int c);

// Splits the pair's larger side (through mirror chain `c` when c >= 0)
// and refines the pairs with its children.
void split_pair(refine_context& ctx, int i, int j, int c = -1) {
  const cluster_node& r = ctx.solver.tree.nodes[i];
  const cluster_node& s = ctx.solver.tree.nodes[j];
  const bool split_receiver = !r.leaf() && (s.leaf() || r.area >= s.area);
  const cluster_node& split = split_receiver ? r : s;
  auto body = [&](int k) {
    const int a = split_receiver ? k : i, b = split_receiver ? j : k;
    c < 0 ? refine_pair(ctx, a, b) : refine_pair_through(ctx, a, b, c);
  };
  // Large pairs fan out over the threads; small ones stay on this one.
  if (ctx.solver.params.parallel && r.elements + s.elements > 4096) {
    tbb::parallel_for(split.first_child, split.first_child + split.child_count, body);
  } else {
    for (int k = split.first_child; k < split.first_child + split.child_count; ++k) body(k);
  }
}

// The oracle's decision for a pair: split, or keep as one link.
void refine_pair(refine_context& ctx, int i, int j) {
  const link_estimate e = estimate(ctx.solver, i, j);
  if (e.none) return;
  const cluster_node& r = ctx.solver.tree.nodes[i];
  const cluster_node& s = ctx.solver.tree.nodes[j];
  const bool splittable = !(r.leaf() && s.leaf()) && !ctx.limit_hit.load(std::memory_order_relaxed);
  const pair_error error = charge(ctx.solver, ctx.node_b, i, j, e);
  if (splittable && (error.split > ctx.tolerance)) return split_pair(ctx, i, j);
  const bool leaves = r.leaf() && s.leaf();
  const int rays = leaves ? ctx.solver.params.leaf_visibility_rays : ctx.solver.params.visibility_rays;
  const float v = visibility(ctx, i, j, rays);
  // Partly visible links must carry less (params.partial_factor).
  if (splittable && v > 0.0f && v < 1.0f && ctx.solver.params.partial_factor * error.bf > ctx.tolerance)
    return split_pair(ctx, i, j);
  // A pair whose estimate is 0 but that is not culled is kept: parts of
  // it may face each other, and a later refinement (with more light) splits it.
  if (!(e.factor > 0.0) && leaves) return;
  if (leaves) mark_split(ctx, i, j, e.factor, v);
  // The oracle decides on the disc estimate; a kept link from an inner
  // node to an oriented receiver carries the strata estimate, except in a
  // closed scene, whose normaliser already takes out the disc estimate's
  // shortfall (docs/hierarchical.md, "What a kept link carries").
  const double factor = !s.leaf() && r.oriented && !ctx.solver.progress.closed
                            ? strata_factor(ctx.solver.tree, *ctx.solver.mesh, j, r.centroid, r.normal)
                            : e.factor;
  ctx.out.local().push_back({i, j, float(factor), v});
  if (ctx.count.fetch_add(1, std::memory_order_relaxed) + 1 >= ctx.solver.params.max_links)
    ctx.limit_hit.store(true, std::memory_order_relaxed);
}

// ---- links through mirror chains ----
//
// The same oracle on the source's image: a pair (receiver, source, chain)
// is culled when the two cannot see each other through the chain's first
// mirror (mirror_chains.h), estimated by the disc estimate to the image
// (leaves: Lambert's formula on the reflected triangle) times kr, and
// split on the larger side while it would carry more than the tolerance.
// A pair that no ray passes is split, as a partly visible one is, while
// it could carry enough to matter, and dropped after that: most pairs
// through a mirror see it partly or not at all, and keeping those that
// see nothing would cost memory for nothing.

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

link_estimate estimate_through(const hierarchical_solver& solver, int i, int j, const mirror_chain& chain) {
  const cluster_node& r = solver.tree.nodes[std::size_t(i)];
  const cluster_node& s = solver.tree.nodes[std::size_t(j)];
  const mirror_set& mirrors = *solver.context.mirrors;
  const planar_mirror& last = mirrors.mirrors[std::size_t(chain.path.mirrors[std::size_t(chain.path.count - 1)])];
  link_estimate e;
  e.none = true;
  if (!box_reaches_in_front(last, s.lo, s.hi, mirrors.tolerance)) return e;
  const image_of_node image = node_image(s, chain);
  const double slack = 1e-9 * solver.mesh->scene_diagonal;
  if ((r.oriented && behind(r.normal, image.lo, image.hi, r.lo, r.hi, slack)) ||
      (s.oriented && behind(image.normal, r.lo, r.hi, image.lo, image.hi, slack)) ||
      !may_cross_first_mirror(mirrors, chain, r.lo, r.hi, image.lo, image.hi))
    return e;
  e.none = false;
  const vec3 d = image.centroid - r.centroid;
  const double r2 = glm::dot(d, d);
  if (r.leaf() && s.leaf()) {
    const glm::ivec3 t = solver.mesh->elements[std::size_t(s.element)];
    const vec3 polygon[3] = {chain.image(solver.mesh->positions[t[0]]), chain.image(solver.mesh->positions[t[1]]),
                             chain.image(solver.mesh->positions[t[2]])};
    e.factor = e.bound = point_polygon_form_factor(r.centroid, r.normal, polygon);
    e.none = !(e.factor > 0.0);
    return e;
  }
  e.factor = disc_factor(s, r.centroid, r.oriented ? &r.normal : nullptr, &chain);
  const bool close = std::sqrt(r2) < r.radius() + s.radius();
  e.bound = close ? 1.0 : std::max(e.factor, 0.1 * s.area / (std::numbers::pi * r2 + s.area));
  return e;
}

// The oracle's charge for a pair through a chain: F x kr x B x A, or,
// from an inner node, what the point kernel's spread over the node's
// sample elements could carry if its light came from one end of it, when
// that is more.
double charge_through(const refine_context& ctx, int i, int j, int c, const link_estimate& e) {
  const hierarchical_solver& solver = ctx.solver;
  const cluster_node& r = solver.tree.nodes[std::size_t(i)];
  const cluster_node& s = solver.tree.nodes[std::size_t(j)];
  const mirror_chain& chain = solver.chains[std::size_t(c)];
  const double transfer = channel_max(chain.path.kr) * r.area * channel_max(ctx.node_b[std::size_t(j)]);
  double bound = e.bound;
  if (!s.leaf()) {
    double lo = INFINITY, hi = 0.0;
    for (const int element : solver.tree.strata[std::size_t(j)]) {
      const glm::ivec3 t = solver.mesh->elements[std::size_t(element)];
      const vec3 q = chain.image(
          (solver.mesh->positions[t[0]] + solver.mesh->positions[t[1]] + solver.mesh->positions[t[2]]) / 3.0);
      const vec3 n = chain.image_direction(solver.mesh->element_normals[std::size_t(element)]);
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
  return bound * transfer;
}

void keep_link_through(refine_context& ctx, int i, int j, int c, double factor, float v) {
  ctx.mirror_out->local().push_back({{i, j, float(factor), v}, c});
  if (ctx.count.fetch_add(1, std::memory_order_relaxed) + 1 >= ctx.solver.params.max_links)
    ctx.limit_hit.store(true, std::memory_order_relaxed);
}

void refine_pair_through(refine_context& ctx, int i, int j, int c) {
  const link_estimate e = estimate_through(ctx.solver, i, j, ctx.solver.chains[std::size_t(c)]);
  if (e.none) return;
  const cluster_node& r = ctx.solver.tree.nodes[std::size_t(i)];
  const cluster_node& s = ctx.solver.tree.nodes[std::size_t(j)];
  const bool leaves = r.leaf() && s.leaf();
  const bool splittable = !leaves && !ctx.limit_hit.load(std::memory_order_relaxed);
  const double error = charge_through(ctx, i, j, c, e);
  if (splittable && error > ctx.tolerance) return split_pair(ctx, i, j, c);
  const int rays = leaves ? ctx.solver.params.leaf_visibility_rays : ctx.solver.params.visibility_rays;
  const float v = visibility(ctx, i, j, rays, c);
  if (splittable && v < 1.0f && ctx.solver.params.partial_factor * error > ctx.tolerance)
    return split_pair(ctx, i, j, c);
  if (v == 0.0f || !(e.factor > 0.0)) return;
  if (leaves) mark_split(ctx, i, j, e.factor, v, &ctx.solver.chains[std::size_t(c)]);
  keep_link_through(ctx, i, j, c, e.factor, v);
}

// A node with itself: its children with each other, and each with itself.
// Oriented nodes do not see themselves.
void refine_self(refine_context& ctx, int i) {
  const cluster_node& node = ctx.solver.tree.nodes[i];
  if (node.oriented || node.leaf()) return;
  auto body = [&](int a) {
    refine_self(ctx, a);
    for (int b = node.first_child; b < node.first_child + node.child_count; ++b)
      if (b != a) refine_pair(ctx, a, b);
  };
  if (ctx.solver.params.parallel && node.elements > 4096)
    tbb::parallel_for(node.first_child, node.first_child + node.child_count, body);
  else
    for (int a = node.first_child; a < node.first_child + node.child_count; ++a) body(a);
}

// Whether sampled rays from the elements all stay inside: a closed scene.
bool scene_is_closed(const hierarchical_solver& solver) {
  const patch_mesh& mesh = *solver.mesh;
  const std::size_t count = mesh.element_count();
  if (count == 0) return false;
  const std::size_t stride = std::max<std::size_t>(1, count / 4096);
  std::atomic<bool> escaped{false};
  const double far = 4.0 * mesh.scene_diagonal;
  for_each_block(solver.params.parallel, (count + stride - 1) / stride, 64, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e && !escaped; ++k) {
      const std::size_t el = k * stride;
      const cluster_node& leaf = solver.tree.nodes[solver.tree.leaf_of_element[el]];
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

// Sorts the links (plain and through mirrors) by receiver and indexes them.
void index_links(hierarchical_solver& solver) {
  tbb::parallel_sort(solver.links.begin(), solver.links.end(), [](const hierarchy_link& a, const hierarchy_link& b) {
    return a.receiver != b.receiver ? a.receiver < b.receiver : a.source < b.source;
  });
  tbb::parallel_sort(solver.mirror_links.begin(), solver.mirror_links.end(),
                     [](const mirror_link& a, const mirror_link& b) {
                       if (a.link.receiver != b.link.receiver) return a.link.receiver < b.link.receiver;
                       return a.chain != b.chain ? a.chain < b.chain : a.link.source < b.link.source;
                     });
  const std::size_t n = solver.tree.nodes.size();
  solver.link_offsets.assign(n + 1, 0);
  for (const hierarchy_link& l : solver.links) ++solver.link_offsets[std::size_t(l.receiver) + 1];
  for (std::size_t i = 0; i < n; ++i) solver.link_offsets[i + 1] += solver.link_offsets[i];
  solver.mirror_link_offsets.assign(n + 1, 0);
  for (const mirror_link& l : solver.mirror_links) ++solver.mirror_link_offsets[std::size_t(l.link.receiver) + 1];
  for (std::size_t i = 0; i < n; ++i) solver.mirror_link_offsets[i + 1] += solver.mirror_link_offsets[i];
}

void update_normalizer(hierarchical_solver& solver) {
  const std::size_t n = solver.mesh->element_count();
  solver.normalizer.assign(n, 1.0);
  if (!solver.progress.closed) return;
  // The form-factor sum of each element: its irradiance when every node has radiosity 1.
  std::vector<rgb> ones(n, rgb(1.0)), sum;
  gather_push(solver, ones, sum);
  for (std::size_t e = 0; e < n; ++e)
    if (sum[e].r > 0.0) solver.normalizer[e] = 1.0 / sum[e].r;
}

// The lamp's direct part: the point lights straight, not by way of mirrors and glass.
rgb direct_lamp(const hierarchical_solver& solver, std::size_t e) {
  return solver.specular_lamp.empty() ? solver.lamp[e] : solver.lamp[e] - solver.specular_lamp[e];
}

// The form-factor context on the input mesh, with its vertices' areas
// (which specular paths deposit over).
form_factor_context input_context(const hierarchical_solver& solver) {
  const patch_mesh& mesh = *solver.input_mesh;
  form_factor_context context = solver.context;
  context.mesh = &mesh;
  context.vertex_areas.assign(mesh.vertex_count(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) context.vertex_areas[std::size_t(mesh.elements[e][k])] += mesh.element_areas[e] / 3.0;
  return context;
}

// Per element of `mesh`, the mean of its vertices' values.
std::vector<rgb> vertex_to_element(const patch_mesh& mesh, const std::vector<rgb>& vertex) {
  std::vector<rgb> out(mesh.element_count());
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    out[e] = (vertex[std::size_t(t[0])] + vertex[std::size_t(t[1])] + vertex[std::size_t(t[2])]) / 3.0;
  }
  return out;
}

// The specular surfaces that paths are sent toward (null: none, or paths off).
std::shared_ptr<const specular_surfaces> path_targets(const hierarchical_solver& solver) {
  return solver.context.params.specular_paths > 0
             ? find_specular_surfaces(*solver.source, *solver.input_mesh, solver.context.mirrors.get())
             : nullptr;
}

// The light of the emitters and point lights by way of mirrors and glass,
// per element of the input mesh (the mean of its vertices'), or nothing
// when the transfer is off or the scene has nothing specular.
std::vector<rgb> specular_lamp_of(const hierarchical_solver& solver, std::uint64_t& rays) {
  const scene& s = *solver.source;
  const form_factor_params& p = solver.context.params;
  if (!p.specular_transfer || !has_specular_materials(s)) return {};
  const std::shared_ptr<const specular_surfaces> surfaces = path_targets(solver);
  if (!surfaces && !solver.context.mirrors) return {};
  const form_factor_context context = input_context(solver);
  return vertex_to_element(*solver.input_mesh,
                           specular_light_from_sources(s, context, surfaces.get(), rays, solver.chains.empty()));
}

// The diffuse light that mirrors and glass pass on, per element of the
// input mesh: every patch radiating the area-weighted mean of its
// elements' reflected radiosity B - E, carried as specular_lamp_of
// carries the emitters'.
std::vector<rgb> passed_on_specular_light(hierarchical_solver& solver, std::uint64_t& rays) {
  const patch_mesh& mesh = *solver.mesh;
  const patch_mesh& input = *solver.input_mesh;
  std::vector<rgb> reflected(input.patch_count(), rgb(0.0));
  std::vector<double> area(input.patch_count(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::size_t p = std::size_t(mesh.element_patches[e]);
    if (p >= reflected.size()) continue;
    reflected[p] += glm::max(solver.radiosity[e] - solver.emission[e], rgb(0.0)) * mesh.element_areas[e];
    area[p] += mesh.element_areas[e];
  }
  for (std::size_t p = 0; p < reflected.size(); ++p) reflected[p] = area[p] > 0.0 ? reflected[p] / area[p] : rgb(0.0);
  const std::shared_ptr<const specular_surfaces> surfaces = path_targets(solver);
  form_factor_context context = input_context(solver);
  // A quarter of the shadow rays and paths of a shot: every patch sends
  // light this way, and their noise averages out over the receivers.
  context.params.shadow_rays = std::max(1, context.params.shadow_rays / 4);
  context.params.specular_paths = std::max(1, context.params.specular_paths / 4);
  // Seeds apart from the emitters' paths, and from pass to pass.
  std::uint64_t seed = (solver.context.params.seed + 0x51ED27ull * std::uint64_t(solver.progress.specular_passes + 1)) *
                       0xD1B54A32D192ED03ull;
  return vertex_to_element(
      input, specular_light_from_patches(*solver.source, context, surfaces.get(), reflected, seed, rays,
                                         solver.progress.specular_ray_budget, &solver.progress.specular_shot_fraction,
                                         solver.chains.empty()));
}

// Sets the lamp's part by way of mirrors and glass to `per_input` (per
// element of the input mesh; the pieces of a split element take its value).
void set_specular_lamp(hierarchical_solver& solver, const std::vector<rgb>& per_input) {
  for (std::size_t e = 0; e < solver.specular_lamp.size(); ++e) {
    const rgb next = per_input[std::size_t(solver.input_element[e])];
    solver.lamp[e] += next - solver.specular_lamp[e];
    solver.specular_lamp[e] = next;
  }
}

// E + lamp: what the system's right-hand side is.
std::vector<rgb> right_hand_side(const hierarchical_solver& solver) {
  std::vector<rgb> b(solver.emission.size());
  for (std::size_t e = 0; e < b.size(); ++e) b[e] = solver.emission[e] + solver.lamp[e];
  return b;
}

void update_residual(hierarchical_solver& solver) {
  const patch_mesh& mesh = *solver.mesh;
  std::vector<rgb> kx;
  apply_transport(solver, solver.radiosity, kx);
  ++solver.progress.operator_applications;
  solver.residual.resize(kx.size());
  // Summed per block, then over the blocks in order: the same total on
  // any number of threads.
  const std::size_t block = 16384, blocks = (kx.size() + block - 1) / block;
  std::vector<double> power(blocks, 0.0);
  for_each_block(solver.params.parallel, blocks, 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k)
      for (std::size_t el = k * block; el < std::min(kx.size(), (k + 1) * block); ++el) {
        solver.residual[el] = solver.emission[el] + solver.lamp[el] + kx[el] - solver.radiosity[el];
        const rgb& r = solver.residual[el];
        power[k] += (std::abs(r.r) + std::abs(r.g) + std::abs(r.b)) * mesh.element_areas[el];
      }
  });
  double total = 0.0;
  for (double p : power) total += p;
  solver.residual_fraction = solver.emitted_power > 0.0 ? total / solver.emitted_power : 0.0;
}

// The direct light (plain links from the emitters, and the point lights
// straight), and the emitters' light through mirror links.
void update_direct(hierarchical_solver& solver) {
  gather_push(solver, solver.emission, solver.direct, &solver.mirrored);
  ++solver.progress.operator_applications;
  for (std::size_t e = 0; e < solver.direct.size(); ++e) {
    solver.direct[e] = solver.rho[e] * (solver.direct[e] * solver.normalizer[e]) + direct_lamp(solver, e);
    solver.mirrored[e] = solver.rho[e] * solver.mirrored[e];
  }
}

}  // namespace

}  // namespace bounce

// ---- BiCGSTAB on I - K, matrix-free (Eigen's documented pattern) ----

namespace bounce {
class transport_system;
}

namespace Eigen::internal {
template <>
struct traits<bounce::transport_system> : public Eigen::internal::traits<Eigen::SparseMatrix<double>> {};
}  // namespace Eigen::internal

namespace bounce {

// (I - K) on vectors of 3 x elements doubles (channels interleaved).
class transport_system : public Eigen::EigenBase<transport_system> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic, IsRowMajor = false };

  explicit transport_system(const hierarchical_solver& solver) : solver_(&solver) {}
  Eigen::Index rows() const { return Eigen::Index(3 * solver_->mesh->element_count()); }
  Eigen::Index cols() const { return rows(); }

  template <typename rhs>
  Eigen::Product<transport_system, rhs, Eigen::AliasFreeProduct> operator*(const Eigen::MatrixBase<rhs>& x) const {
    return Eigen::Product<transport_system, rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }

  void apply(const double* in, double* out) const {
    const std::size_t n = solver_->mesh->element_count();
    std::vector<rgb>& x = x_;
    x.resize(n);
    const bool parallel = solver_->params.parallel;
    for_each_block(parallel, n, 16384, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) x[i] = rgb(in[3 * i], in[3 * i + 1], in[3 * i + 2]);
    });
    apply_transport(*solver_, x, kx_);
    for_each_block(parallel, n, 16384, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i)
        for (int c = 0; c < 3; ++c) out[3 * i + c] = x[i][c] - kx_[i][c];
    });
    ++applications;
  }
  mutable std::uint64_t applications = 0;

 private:
  const hierarchical_solver* solver_;
  mutable std::vector<rgb> x_, kx_;
};

}  // namespace bounce

namespace Eigen::internal {
template <typename rhs>
struct generic_product_impl<bounce::transport_system, rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<bounce::transport_system, rhs, generic_product_impl<bounce::transport_system, rhs>> {
  using Scalar = typename Product<bounce::transport_system, rhs>::Scalar;
  template <typename dest>
  static void scaleAndAddTo(dest& dst, const bounce::transport_system& lhs, const rhs& x, const Scalar& alpha) {
    const Eigen::VectorXd in = x;
    Eigen::VectorXd out(in.size());
    lhs.apply(in.data(), out.data());
    dst += alpha * out;
  }
};
}  // namespace Eigen::internal

namespace bounce {

void apply_transport(const hierarchical_solver& solver, const std::vector<rgb>& x, std::vector<rgb>& out) {
  const bool mirrors = !solver.mirror_links.empty();
  std::vector<rgb>& mirrored = solver.buffers.mirrored;
  gather_push(solver, x, out, mirrors ? &mirrored : nullptr);
  for_each_block(solver.params.parallel, out.size(), 16384, [&](std::size_t b, std::size_t end) {
    for (std::size_t e = b; e < end; ++e)
      out[e] = solver.rho[e] * (out[e] * solver.normalizer[e] + (mirrors ? mirrored[e] : rgb(0.0)));
  });
}

namespace {

// Everything that follows from the mesh and its tree: the operator's
// working arrays, and per element rho, E, the point lights' light and the
// emitted power. Drops the links; leaves the solution to the caller.
void build_for_mesh(hierarchical_solver& solver, cluster_tree tree) {
  const patch_mesh& mesh = *solver.mesh;
  const scene& s = *solver.source;
  solver.context.mesh = &mesh;
  solver.tree = std::move(tree);
  solver.cube_slot.assign(solver.tree.nodes.size(), -1);
  int slots = 0;
  for (std::size_t i = 0; i < solver.tree.nodes.size(); ++i)
    if (!solver.tree.nodes[i].oriented) solver.cube_slot[i] = slots++;
  solver.buffers.node_b.resize(solver.tree.nodes.size());
  solver.buffers.gathered.resize(solver.tree.nodes.size());
  solver.buffers.bins.resize(std::size_t(slots));
  solver.links.clear();
  solver.link_offsets.assign(solver.tree.nodes.size() + 1, 0);
  solver.mirror_links.clear();
  solver.mirror_link_offsets.assign(solver.tree.nodes.size() + 1, 0);
  solver.split_marks.clear();
  solver.split_roots.clear();

  const std::size_t n = mesh.element_count();
  solver.rho.resize(n);
  solver.emission.resize(n);
  solver.lamp.assign(n, rgb(0.0));
  solver.normalizer.assign(n, 1.0);
  std::uint64_t rays = 0;
  for (std::size_t e = 0; e < n; ++e) {
    const glm::ivec3 t = mesh.elements[e];
    solver.rho[e] = (mesh.vertex_rho[t[0]] + mesh.vertex_rho[t[1]] + mesh.vertex_rho[t[2]]) / 3.0;
    solver.emission[e] = (mesh.vertex_emission[t[0]] + mesh.vertex_emission[t[1]] + mesh.vertex_emission[t[2]]) / 3.0;
    if (has_lights_beyond_surfaces(s)) {
      const cluster_node& leaf = solver.tree.nodes[solver.tree.leaf_of_element[e]];
      solver.lamp[e] = solver.rho[e] * point_light_irradiance(s, solver.context, leaf.centroid, leaf.normal, rays);
    }
    if (!solver.specular_lamp.empty()) solver.lamp[e] += solver.specular_lamp[e];
  }
  solver.progress.rays += rays;
  solver.emitted_power = 0.0;
  for (std::size_t e = 0; e < n; ++e) {
    const rgb b = solver.emission[e] + solver.lamp[e];
    solver.emitted_power += (b.r + b.g + b.b) * mesh.element_areas[e];
  }
}

// Element refinement still to make: marks, passes left, no failure.
bool splits_pending(const hierarchical_solver& solver) {
  return solver.params.split_elements && !solver.split_marks.empty() &&
         solver.progress.element_passes < solver.params.max_element_passes && solver.progress.warning.empty();
}

}  // namespace

std::unique_ptr<hierarchical_solver> make_hierarchical_solver(const scene& s, const patch_mesh& mesh,
                                                              const form_factor_context& context,
                                                              const hierarchical_params& params) {
  auto solver = std::make_unique<hierarchical_solver>();
  solver->mesh = solver->input_mesh = &mesh;
  solver->source = &s;
  solver->params = params;
  solver->context = context;
  solver->context.vertex_areas.clear();  // the solver works per element
  solver->min_edge = params.min_edge > 0.0 ? params.min_edge : mesh.max_edge / 8.0;
  if (params.mirror_links && context.mirrors && context.params.specular_transfer)
    solver->chains = mirror_chains(*context.mirrors, context.params.mirror_depth);
  solver->has_path_targets = path_targets(*solver) != nullptr;
  solver->specular_lamp_input = specular_lamp_of(*solver, solver->progress.rays);
  solver->specular_lamp = solver->specular_lamp_input;
  solver->input_element.resize(mesh.element_count());
  for (std::size_t e = 0; e < mesh.element_count(); ++e) solver->input_element[e] = int(e);
  build_for_mesh(*solver, build_cluster_tree(mesh));
  solver->progress.closed = params.normalize_closed && scene_is_closed(*solver);
  restart_hierarchical(*solver);
  return solver;
}

void restart_hierarchical(hierarchical_solver& solver) {
  if (solver.mesh != solver.input_mesh) {
    solver.mesh = solver.input_mesh;
    solver.refined_mesh.reset();
    solver.specular_lamp = solver.specular_lamp_input;
    solver.input_element.resize(solver.mesh->element_count());
    for (std::size_t e = 0; e < solver.input_element.size(); ++e) solver.input_element[e] = int(e);
    build_for_mesh(solver, build_cluster_tree(*solver.mesh));
  }
  if (solver.progress.specular_passes > 0) set_specular_lamp(solver, solver.specular_lamp_input);
  solver.links.clear();
  solver.link_offsets.assign(solver.tree.nodes.size() + 1, 0);
  solver.mirror_links.clear();
  solver.mirror_link_offsets.assign(solver.tree.nodes.size() + 1, 0);
  solver.split_marks.clear();
  solver.normalizer.assign(solver.mesh->element_count(), 1.0);
  solver.radiosity = right_hand_side(solver);
  solver.direct.resize(solver.lamp.size());
  for (std::size_t e = 0; e < solver.lamp.size(); ++e) solver.direct[e] = direct_lamp(solver, e);
  solver.mirrored.assign(solver.lamp.size(), rgb(0.0));
  solver.residual.assign(solver.radiosity.size(), rgb(0.0));
  solver.residual_fraction = 1.0;
  const std::uint64_t rays = solver.progress.rays;
  const bool closed = solver.progress.closed;
  solver.progress = hierarchy_progress{};
  solver.progress.rays = rays;
  solver.progress.closed = closed;
  const double final_tolerance = solver.params.tolerance;
  solver.progress.tolerance = final_tolerance * std::pow(solver.params.refine_factor, solver.params.rounds);
}

bool refinement_done(const hierarchical_solver& solver) {
  return solver.progress.links_final && !splits_pending(solver);
}

bool specular_passes_done(const hierarchical_solver& solver) {
  // With links through mirrors, the passes have only paths to carry.
  return solver.specular_lamp.empty() || solver.progress.specular_passes >= solver.params.specular_bounces ||
         (!solver.chains.empty() && !solver.has_path_targets);
}

bool split_marked_elements(hierarchical_solver& solver) {
  if (solver.split_marks.empty()) return false;
  const std::size_t n = solver.mesh->element_count();
  auto refined = std::make_shared<patch_mesh>(*solver.mesh);
  std::vector<int> marked, times, from;  // from[e]: the element of solver.mesh that element e lies in
  for (std::size_t e = 0; e < n; ++e)
    if (solver.split_marks[e] > 0) {
      marked.push_back(int(e));
      times.push_back(solver.split_marks[e]);
    }
  std::string error;
  bool split = refine_patch_mesh(*refined, marked, solver.min_edge, from, error, times);
  if (!split) solver.progress.warning = "element refinement stopped: " + error;
  split = split && refined->element_count() > n;
  solver.split_marks.clear();
  ++solver.progress.element_passes;
  if (!split) return false;

  // The old tree continues with subtrees over the pieces, so the links
  // stay (renumbered); the next link refinement splits those that the
  // pieces now allow. Each piece keeps its element's radiosity: the
  // piecewise-constant solution is unchanged, and iterating goes on from it.
  std::vector<int> node_of_old;
  cluster_tree tree = extend_cluster_tree(solver.tree, *refined, from, node_of_old);
  std::vector<std::uint8_t> split_roots(tree.nodes.size(), 0);
  for (std::size_t o = 0; o < node_of_old.size(); ++o)
    if (solver.tree.nodes[o].leaf() && !tree.nodes[std::size_t(node_of_old[o])].leaf())
      split_roots[std::size_t(node_of_old[o])] = 1;
  std::vector<hierarchy_link> links = std::move(solver.links);
  for (hierarchy_link& link : links) {
    link.receiver = node_of_old[std::size_t(link.receiver)];
    link.source = node_of_old[std::size_t(link.source)];
  }
  std::vector<mirror_link> mirror_links = std::move(solver.mirror_links);
  for (mirror_link& m : mirror_links) {
    m.link.receiver = node_of_old[std::size_t(m.link.receiver)];
    m.link.source = node_of_old[std::size_t(m.link.source)];
  }
  const std::vector<rgb> radiosity = std::move(solver.radiosity), direct = std::move(solver.direct);
  const std::vector<rgb> mirrored = std::move(solver.mirrored);
  solver.refined_mesh = refined;
  solver.mesh = refined.get();
  if (!solver.specular_lamp.empty()) {
    std::vector<rgb> pieces(refined->element_count());
    for (std::size_t e = 0; e < pieces.size(); ++e) pieces[e] = solver.specular_lamp[std::size_t(from[e])];
    solver.specular_lamp = std::move(pieces);
  }
  std::vector<int> input_element(refined->element_count());
  for (std::size_t e = 0; e < input_element.size(); ++e) input_element[e] = solver.input_element[std::size_t(from[e])];
  solver.input_element = std::move(input_element);
  build_for_mesh(solver, std::move(tree));
  solver.links = std::move(links);
  solver.mirror_links = std::move(mirror_links);
  index_links(solver);
  const std::size_t m = solver.mesh->element_count();
  solver.radiosity.resize(m);
  solver.direct.resize(m);
  solver.mirrored.resize(m);
  for (std::size_t e = 0; e < m; ++e) {
    solver.radiosity[e] = radiosity[std::size_t(from[e])];
    solver.direct[e] = direct[std::size_t(from[e])];
    solver.mirrored[e] = mirrored[std::size_t(from[e])];
  }
  solver.residual.assign(m, rgb(0.0));
  solver.gathered.clear();
  solver.gathered_direct.clear();
  solver.gathered_mirrored.clear();
  return true;
}

void refine_links(hierarchical_solver& solver, double tolerance) {
  if (solver.tree.nodes.empty()) return;
  std::vector<rgb> node_b(solver.tree.nodes.size());
  pull(solver, solver.radiosity, node_b, nullptr);  // the oracle charges the mean
  tbb::enumerable_thread_specific<std::vector<hierarchy_link>> out;
  std::atomic<std::size_t> count{0};
  std::atomic<std::uint64_t> rays{0};
  std::atomic<bool> limit_hit{false};
  tbb::enumerable_thread_specific<std::vector<std::pair<int, int>>> marks;
  // The tolerance is relative to the power leaving all surfaces now (at
  // least the emitted power): at high reflectance far more power circulates
  // than is emitted, and each link's share of it is what matters.
  double leaving = 0.0;
  for (std::size_t e = 0; e < solver.radiosity.size(); ++e)
    leaving += std::max(0.0, channel_sum(solver.radiosity[e])) * solver.mesh->element_areas[e];
  const double power = std::max(leaving, solver.emitted_power) / 3.0;
  refine_context ctx{solver, node_b, tolerance * power, out, count, rays, limit_hit, marks};
  if (solver.links.empty()) {
    refine_self(ctx, 0);
  } else {
    const std::vector<hierarchy_link>& old = solver.links;
    for_each_block(solver.params.parallel, old.size(), 256, [&](std::size_t b, std::size_t e) {
      for (std::size_t l = b; l < e; ++l) {
        const hierarchy_link& link = old[l];
        if (!solver.split_roots.empty() && !solver.split_roots[std::size_t(link.receiver)] &&
            !solver.split_roots[std::size_t(link.source)]) {
          out.local().push_back(link);  // examined at this tolerance already
          count.fetch_add(1, std::memory_order_relaxed);
          continue;
        }
        const cluster_node& r = solver.tree.nodes[link.receiver];
        const cluster_node& s = solver.tree.nodes[link.source];
        const bool splittable = !(r.leaf() && s.leaf()) && !limit_hit.load(std::memory_order_relaxed);
        const link_estimate est = estimate(solver, link.receiver, link.source);
        const pair_error error = charge(solver, node_b, link.receiver, link.source, est);
        const bool partial = link.visibility > 0.0f && link.visibility < 1.0f;
        if (splittable &&
            (error.split > ctx.tolerance || (partial && solver.params.partial_factor * error.bf > ctx.tolerance))) {
          split_pair(ctx, link.receiver, link.source);
        } else {
          if (r.leaf() && s.leaf()) mark_split(ctx, link.receiver, link.source, est.factor, link.visibility);
          out.local().push_back(link);
          if (count.fetch_add(1, std::memory_order_relaxed) + 1 >= solver.params.max_links) limit_hit = true;
        }
      }
    });
  }
  // Links through mirror chains: made afresh from the roots at every
  // refinement (they are few, and a pair that no ray passed at a coarse
  // tolerance may matter at a finer one).
  tbb::enumerable_thread_specific<std::vector<mirror_link>> mirror_out;
  ctx.mirror_out = &mirror_out;
  for_each_block(solver.params.parallel, solver.chains.size(), 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t c = b; c < e; ++c) refine_pair_through(ctx, 0, 0, int(c));
  });
  std::vector<hierarchy_link> links;
  links.reserve(count.load());
  for (auto& part : out) links.insert(links.end(), part.begin(), part.end());
  solver.links = std::move(links);
  solver.mirror_links.clear();
  for (auto& part : mirror_out) solver.mirror_links.insert(solver.mirror_links.end(), part.begin(), part.end());
  index_links(solver);
  solver.split_roots.clear();
  solver.split_marks.clear();
  std::size_t marked = 0;
  for (const auto& part : marks)
    for (const auto& [element, bisections] : part) {
      if (solver.split_marks.empty()) solver.split_marks.assign(solver.mesh->element_count(), 0);
      std::uint8_t& m = solver.split_marks[std::size_t(element)];
      marked += m == 0 ? 1 : 0;
      m = std::max(m, std::uint8_t(bisections));
    }
  solver.progress.split_marks += marked;
  if (double(marked) < solver.params.min_marked_fraction * double(solver.mesh->element_count()))
    solver.split_marks.clear();
  solver.progress.rays += rays.load();
  ++solver.progress.refinements;
  if (limit_hit)
    solver.progress.warning = "link limit reached (" + std::to_string(solver.links.size()) + " links, " +
                              std::to_string(solver.links.size() * sizeof(hierarchy_link) >> 20) +
                              " MiB): the solution keeps coarser links there";
  update_normalizer(solver);
}

bool step_hierarchical(hierarchical_solver& solver, double refine_below) {
  if (!(refinement_done(solver) && solver.residual_fraction <= 1e-13)) ++solver.progress.steps;
  const double final_tolerance = solver.params.tolerance;
  if (solver.link_offsets.back() == 0 && solver.progress.refinements == 0) {
    // First step: the coarsest links, then one Jacobi sweep from B = E: the direct light.
    refine_links(solver, solver.progress.tolerance);
    solver.progress.links_final = solver.progress.tolerance <= final_tolerance * (1.0 + 1e-9);
    update_direct(solver);
    std::vector<rgb> kx;
    apply_transport(solver, solver.radiosity, kx);
    ++solver.progress.operator_applications;
    const std::vector<rgb> b = right_hand_side(solver);
    for (std::size_t e = 0; e < kx.size(); ++e) solver.radiosity[e] = b[e] + kx[e];
    update_residual(solver);
    return true;
  }
  // Refine once this tolerance is solved far enough, or when iterating no
  // longer helps (a residual that falls by less than 5% a step): first the
  // elements the last links marked (against the solution as it is now),
  // then the links at the next tolerance, or at the final one again.
  const bool stalled = solver.residual_fraction > 0.95 * solver.progress.previous_residual;
  solver.progress.previous_residual = solver.residual_fraction;
  if ((solver.residual_fraction <= refine_below || stalled) && !refinement_done(solver)) {
    solver.progress.previous_residual = INFINITY;
    const bool remeshed = splits_pending(solver) && split_marked_elements(solver);
    const double next = std::max(final_tolerance, solver.progress.tolerance / solver.params.refine_factor);
    if (next < solver.progress.tolerance || remeshed) {
      if (next < solver.progress.tolerance) solver.split_roots.clear();  // a new tolerance: every link
      solver.progress.tolerance = next;
      solver.progress.links_final = solver.progress.tolerance <= final_tolerance * (1.0 + 1e-9);
      refine_links(solver, solver.progress.tolerance);
      update_direct(solver);
    }
    update_residual(solver);
    return true;
  }
  // The final links solved: diffuse light that mirrors and glass pass on
  // joins the right-hand side, one pass at a time (params.specular_bounces).
  if (refinement_done(solver) && solver.residual_fraction <= refine_below && !specular_passes_done(solver)) {
    if (solver.progress.specular_passes == 0)
      solver.progress.specular_ray_budget =
          std::max(solver.params.specular_min_rays,
                   std::uint64_t(solver.params.specular_ray_share * double(solver.progress.rays)));
    std::vector<rgb> light = passed_on_specular_light(solver, solver.progress.rays);
    for (std::size_t e = 0; e < light.size(); ++e) light[e] += solver.specular_lamp_input[e];
    set_specular_lamp(solver, light);
    ++solver.progress.specular_passes;
    solver.progress.previous_residual = INFINITY;
    update_residual(solver);
    return true;
  }
  if (refinement_done(solver) && solver.residual_fraction <= 1e-13) return false;

  const std::size_t n = solver.mesh->element_count();
  Eigen::VectorXd b(3 * Eigen::Index(n)), x(3 * Eigen::Index(n));
  const std::vector<rgb> rhs = right_hand_side(solver);
  for (std::size_t e = 0; e < n; ++e)
    for (int c = 0; c < 3; ++c) {
      b[3 * Eigen::Index(e) + c] = rhs[e][c];
      x[3 * Eigen::Index(e) + c] = solver.radiosity[e][c];
    }
  transport_system system(solver);
  Eigen::BiCGSTAB<transport_system, Eigen::IdentityPreconditioner> bicgstab;
  bicgstab.setMaxIterations(solver.params.iterations_per_step);
  // Before the links are final, this tolerance only needs solving as far
  // as the next refinement: stop there (Eigen's relative 2-norm residual).
  bicgstab.setTolerance(refinement_done(solver) ? 1e-14 : 0.5 * refine_below);
  bicgstab.compute(system);
  Eigen::VectorXd next = bicgstab.solveWithGuess(b, x);
  if (bicgstab.iterations() == 0) {
    // Eigen's norm says solved where the area-weighted residual does not: go on.
    bicgstab.setTolerance(1e-14);
    next = bicgstab.solveWithGuess(b, x);
  }
  solver.progress.operator_applications += system.applications;
  const std::vector<rgb> before = solver.radiosity;
  const double residual_before = solver.residual_fraction;
  if (next.allFinite()) {
    for (std::size_t e = 0; e < n; ++e)
      solver.radiosity[e] =
          rgb(next[3 * Eigen::Index(e)], next[3 * Eigen::Index(e) + 1], next[3 * Eigen::Index(e) + 2]);
    update_residual(solver);
    if (solver.residual_fraction < residual_before) return true;
  }
  // BiCGSTAB broke down or made things worse (it can, on a non-normal
  // operator): a Jacobi sweep instead, B = E + K B, which converges
  // whenever every element's form factors sum to less than 1/rho.
  solver.radiosity = before;
  std::vector<rgb> kx;
  apply_transport(solver, solver.radiosity, kx);
  ++solver.progress.operator_applications;
  for (std::size_t e = 0; e < n; ++e) solver.radiosity[e] = rhs[e] + kx[e];
  update_residual(solver);
  ++solver.progress.jacobi_fallbacks;
  return true;
}

std::uint64_t final_gather_cost(const hierarchical_solver& solver) {
  const cluster_tree& tree = solver.tree;
  std::vector<std::uint64_t> chain(tree.nodes.size(), 0);
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    chain[i] = (solver.link_offsets[i + 1] - solver.link_offsets[i]) +
               (solver.mirror_link_offsets[i + 1] - solver.mirror_link_offsets[i]) +
               (i > 0 ? chain[tree.nodes[i].parent] : 0);
    if (tree.nodes[i].leaf()) total += chain[i];
  }
  return total;
}

bool final_gather(hierarchical_solver& solver) {
  if (final_gather_cost(solver) > solver.params.gather_budget) return false;
  const cluster_tree& tree = solver.tree;
  const patch_mesh& mesh = *solver.mesh;
  std::vector<rgb> node_b(tree.nodes.size()), node_e(tree.nodes.size());
  std::vector<std::array<rgb, 6>> sent_b, sent_e;
  pull(solver, solver.radiosity, node_b, &sent_b);
  pull(solver, solver.emission, node_e, &sent_e);
  // Per link from an inner node: its strata estimate over the disc
  // estimate at its receiver's centre. Each element takes the disc
  // estimate at itself times that: the correction is the source's shape,
  // which changes slowly over a receiver that the oracle kept small
  // against the distance.
  std::vector<float> correction(solver.links.size(), 1.0f);
  if (!solver.progress.closed)  // closed scenes' links carry the disc estimate itself
    for_each_block(solver.params.parallel, solver.links.size(), 4096, [&](std::size_t b, std::size_t end) {
      for (std::size_t l = b; l < end; ++l) {
        const hierarchy_link& link = solver.links[l];
        const cluster_node& r = tree.nodes[std::size_t(link.receiver)];
        const cluster_node& s = tree.nodes[std::size_t(link.source)];
        if (s.leaf() || !r.oriented) continue;
        const double at_centre = disc_factor(s, r.centroid, &r.normal);
        if (at_centre > 0.0) correction[l] = float(double(link.factor) / at_centre);
      }
    });
  const std::size_t n = mesh.element_count();
  solver.gathered.assign(n, rgb(0.0));
  solver.gathered_direct.assign(n, rgb(0.0));
  solver.gathered_mirrored.assign(n, rgb(0.0));
  std::atomic<std::uint64_t> evaluations{0};
  for_each_block(solver.params.parallel, n, 256, [&](std::size_t b, std::size_t end) {
    std::uint64_t count = 0;
    for (std::size_t e = b; e < end; ++e) {
      const cluster_node& leaf = tree.nodes[tree.leaf_of_element[e]];
      rgb sum(0.0), direct(0.0);
      double factors = 0.0;
      for (int a = tree.leaf_of_element[e]; a >= 0; a = tree.nodes[a].parent) {
        for (std::size_t l = solver.link_offsets[a]; l < solver.link_offsets[a + 1]; ++l) {
          const hierarchy_link& link = solver.links[l];
          const cluster_node& s = tree.nodes[link.source];
          ++count;
          double f = 0.0, send = 0.0;
          vec3 dir(0.0);
          if (s.leaf()) {
            const glm::ivec3 t = mesh.elements[s.element];
            const vec3 polygon[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
            f = point_polygon_form_factor(leaf.centroid, leaf.normal, polygon);
          } else {
            // The disc estimate at the element, corrected as the link's
            // strata estimate corrects it at its receiver's centre (the
            // correction is the source's shape, which changes slowly over
            // a receiver that the oracle kept small against the distance).
            f = std::min(1.0, disc_factor(s, leaf.centroid, &leaf.normal, dir, send) * double(correction[l]));
          }
          f *= double(link.visibility);
          if (!(f > 0.0)) continue;
          factors += f;
          sum += f * sent_radiosity(solver, node_b, sent_b, link.source, -dir, send);
          direct += f * sent_radiosity(solver, node_e, sent_e, link.source, -dir, send);
        }
      }
      // Through mirror chains: the kernel to the source's image at the
      // element (leaves: Lambert's formula on the reflected triangle).
      rgb mirrored(0.0), mirrored_direct(0.0);
      for (int a = tree.leaf_of_element[e]; a >= 0; a = tree.nodes[a].parent) {
        for (std::size_t l = solver.mirror_link_offsets[a]; l < solver.mirror_link_offsets[a + 1]; ++l) {
          const mirror_link& m = solver.mirror_links[l];
          const mirror_chain& chain = solver.chains[std::size_t(m.chain)];
          const cluster_node& s = tree.nodes[m.link.source];
          ++count;
          vec3 dir;
          double send = 0.0;
          double f = disc_factor(s, leaf.centroid, &leaf.normal, dir, send, &chain);
          if (dir == vec3(0.0)) continue;  // no direction
          const vec3 out = chain.source_direction(-dir);
          if (s.leaf()) {
            const glm::ivec3 t = mesh.elements[s.element];
            const vec3 polygon[3] = {chain.image(mesh.positions[t[0]]), chain.image(mesh.positions[t[1]]),
                                     chain.image(mesh.positions[t[2]])};
            f = point_polygon_form_factor(leaf.centroid, leaf.normal, polygon);
          }
          f *= double(m.link.visibility);
          if (!(f > 0.0)) continue;
          mirrored += f * chain.path.kr * sent_radiosity(solver, node_b, sent_b, m.link.source, out, send);
          mirrored_direct += f * chain.path.kr * sent_radiosity(solver, node_e, sent_e, m.link.source, out, send);
        }
      }
      // The normaliser is for the plain links alone: a mirror's solid
      // angle is counted once, by the links to the mirror itself.
      const double scale = solver.progress.closed && factors > 0.0 ? 1.0 / factors : 1.0;
      solver.gathered[e] = solver.rho[e] * (sum * scale + mirrored);
      solver.gathered_direct[e] = solver.rho[e] * (direct * scale);
      solver.gathered_mirrored[e] = solver.rho[e] * mirrored_direct;
    }
    evaluations += count;
  });
  solver.progress.gather_evaluations += evaluations.load();
  return true;
}

std::vector<rgb> element_to_vertex(const patch_mesh& mesh, const std::vector<rgb>& per_element) {
  std::vector<rgb> sum(mesh.vertex_count(), rgb(0.0));
  std::vector<double> area(mesh.vertex_count(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) {
      sum[mesh.elements[e][k]] += per_element[e] * mesh.element_areas[e];
      area[mesh.elements[e][k]] += mesh.element_areas[e];
    }
  for (std::size_t v = 0; v < sum.size(); ++v)
    if (area[v] > 0.0) sum[v] /= area[v];
  return sum;
}

std::vector<double> link_density(const hierarchical_solver& solver) {
  const cluster_tree& tree = solver.tree;
  std::vector<double> per_node(tree.nodes.size(), 0.0);
  // Links per unit area of their receiver, accumulated down the tree.
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const double links = double(solver.link_offsets[i + 1] - solver.link_offsets[i]);
    const double own = tree.nodes[i].area > 0.0 ? links / tree.nodes[i].area : 0.0;
    per_node[i] = own + (tree.nodes[i].parent >= 0 ? per_node[tree.nodes[i].parent] : 0.0);
  }
  std::vector<double> out(solver.mesh->element_count());
  for (std::size_t e = 0; e < out.size(); ++e) out[e] = per_node[tree.leaf_of_element[e]];
  return out;
}

std::vector<rgb> element_level_solution(const hierarchical_solver& solver) {
  const std::size_t n = solver.mesh->element_count();
  BOUNCE_CHECK(n <= 4000);  // a dense matrix: small scenes only
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(Eigen::Index(n), Eigen::Index(n));
  tbb::enumerable_thread_specific<std::vector<hierarchy_link>> unused;
  std::atomic<std::size_t> count{0};
  std::atomic<std::uint64_t> rays{0};
  std::atomic<bool> limit{false};
  std::vector<rgb> none;
  tbb::enumerable_thread_specific<std::vector<std::pair<int, int>>> no_marks;
  refine_context ctx{solver, none, 0.0, unused, count, rays, limit, no_marks};
  for (std::size_t i = 0; i < n; ++i) {
    const int ri = solver.tree.leaf_of_element[i];
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      const int sj = solver.tree.leaf_of_element[j];
      const link_estimate e = estimate(solver, ri, sj);
      if (e.none || !(e.factor > 0.0)) continue;
      f(Eigen::Index(i), Eigen::Index(j)) =
          double(float(e.factor)) * double(visibility(ctx, ri, sj, solver.params.leaf_visibility_rays));
    }
  }
  if (solver.progress.closed)
    for (Eigen::Index i = 0; i < f.rows(); ++i) {
      const double sum = f.row(i).sum();
      if (sum > 0.0) f.row(i) /= sum;
    }
  std::vector<rgb> b(n);
  for (int c = 0; c < 3; ++c) {
    Eigen::MatrixXd a = -f;
    Eigen::VectorXd right = Eigen::VectorXd::Zero(Eigen::Index(n));
    for (std::size_t i = 0; i < n; ++i) {
      a.row(Eigen::Index(i)) *= solver.rho[i][c];
      a(Eigen::Index(i), Eigen::Index(i)) += 1.0;
      right[Eigen::Index(i)] = solver.emission[i][c] + solver.lamp[i][c];
    }
    const Eigen::VectorXd x = a.partialPivLu().solve(right);
    for (std::size_t i = 0; i < n; ++i) b[i][c] = x[Eigen::Index(i)];
  }
  return b;
}

}  // namespace bounce
