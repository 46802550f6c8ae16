#include "radiosity/hierarchical/final_gather.h"

#include <algorithm>
#include <atomic>
#include <utility>

#include "base/parallel.h"
#include "radiosity/hierarchical/closed_scene.h"
#include "radiosity/hierarchical/node_kernels.h"
#include "radiosity/hierarchical/oracle.h"
#include "radiosity/hierarchical/transport.h"
#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/mirror_images.h"
#include "radiosity/transfer/point_lights.h"

namespace bounce {
namespace {

// The elements around each vertex, in compressed rows.
struct vertex_elements {
  std::vector<std::size_t> offsets;
  std::vector<int> elements;
};

vertex_elements elements_around_vertices(const patch_mesh& mesh) {
  vertex_elements out;
  out.offsets.assign(mesh.vertex_count() + 1, 0);
  for (const glm::ivec3& tri : mesh.elements)
    for (int k = 0; k < 3; ++k) ++out.offsets[std::size_t(tri[k]) + 1];
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) out.offsets[v + 1] += out.offsets[v];
  out.elements.resize(out.offsets.back());
  std::vector<std::size_t> next(out.offsets.begin(), out.offsets.end() - 1);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) out.elements[next[std::size_t(mesh.elements[e][k])]++] = int(e);
  return out;
}

// The nodes above vertex v's elements that have links, each with the share
// of the elements' area under it (1 for the ancestors they all share).
void nodes_above(const hierarchical_solver& solver, const vertex_elements& around, std::size_t v,
                 std::vector<std::pair<int, double>>& out) {
  const cluster_tree& tree = solver.hierarchy.tree;
  const patch_mesh& mesh = solver.mesh();
  out.clear();
  double area = 0.0;
  for (std::size_t i = around.offsets[v]; i < around.offsets[v + 1]; ++i)
    area += mesh.element_areas[std::size_t(around.elements[i])];
  if (!(area > 0.0)) return;
  for (std::size_t i = around.offsets[v]; i < around.offsets[v + 1]; ++i) {
    const int e = around.elements[i];
    const double share = mesh.element_areas[std::size_t(e)] / area;
    for (int a = tree.leaf_of_element[std::size_t(e)]; a >= 0; a = tree.nodes[std::size_t(a)].parent) {
      if (solver.hierarchy.links.count_of(std::size_t(a)) + solver.hierarchy.mirror_links.count_of(std::size_t(a)) == 0)
        continue;
      auto found = std::find_if(out.begin(), out.end(), [a](const auto& node) { return node.first == a; });
      if (found == out.end())
        out.emplace_back(a, share);
      else
        found->second += share;
    }
  }
}

// Light a vertex gathers from one source node: f x B summed for the
// solution and for the emission alone, and the sum of f.
struct gathered_sum {
  rgb b{0.0}, e{0.0};
  double factors = 0.0;
};

// A source is near a point when it is large against its distance: its
// disc estimate, and the correction made at the receiver's centre, no
// longer hold there (a vertex on the edge a wall shares with its lamp).
constexpr double near_ratio = 0.5;

bool near(const cluster_node& source, const vec3& p) {
  return source.radius() > near_ratio * glm::length(source.centroid - p);
}

// A link's correction (strata over disc estimate at its receiver's centre)
// is carried to the vertices only while the two agree within this factor.
// Where they do not, the disc estimate is ill-conditioned there (a source
// seen almost edge-on from the centre): scaled by the ratio, it made bright
// blotches on walls at fine tolerances (interior-10k: 3.5% at 1e-5, 7.2% at
// 5e-6 from the path tracer; 3.5% and 3.1% since).
constexpr double correction_trust = 2.0;

struct gather_inputs {
  const hierarchical_solver& solver;
  const std::vector<rgb>& node_b;
  const std::vector<rgb>& node_e;
  const std::vector<std::array<rgb, 6>>& sent_b;
  const std::vector<std::array<rgb, 6>>& sent_e;
  double in_plane;  // a point this close to a source element's plane sees it edge-on

  void add(int source, double f, const vec3& from, double send, gathered_sum& out) const {
    out.factors += f;
    out.b += f * sent_radiosity(solver, node_b, sent_b, source, from, send);
    out.e += f * sent_radiosity(solver, node_e, sent_e, source, from, send);
  }

  // Lambert's formula from p (normal n) to a source element.
  double leaf_factor(const cluster_node& leaf, const vec3& p, const vec3& n) const {
    const patch_mesh& mesh = solver.mesh();
    const std::size_t e = std::size_t(leaf.element);
    if (glm::dot(mesh.element_normals[e], p - leaf.centroid) <= in_plane) return 0.0;
    return point_polygon_form_factor(p, n, element_corners(mesh, e));
  }

  // An inner source by its strata estimate at p, sending its radiosity
  // towards p.
  void strata_source(int source, const vec3& p, const vec3& n, double weight, gathered_sum& out) const {
    vec3 towards;
    double send = 0.0;
    disc_factor(solver.hierarchy.tree.nodes[std::size_t(source)], p, &n, towards, send);
    const double f = strata_factor(solver.hierarchy.tree, solver.mesh(), source, p, n);
    if (f > 0.0) add(source, weight * f, -towards, send, out);
  }

  // A near inner source, child by child: elements by Lambert's formula,
  // near children the same way down, the others by their strata estimate
  // at p. Each child sends its own radiosity. `weight`: the vertex's share
  // of the link times its visibility.
  void near_source(int source, const vec3& p, const vec3& n, double weight, gathered_sum& out) const {
    const cluster_tree& tree = solver.hierarchy.tree;
    const cluster_node& node = tree.nodes[std::size_t(source)];
    for (int c = node.first_child; c < node.first_child + node.child_count; ++c) {
      const cluster_node& child = tree.nodes[std::size_t(c)];
      if (child.leaf()) {
        const double f = leaf_factor(child, p, n);
        if (f > 0.0) add(c, weight * f, vec3(0.0), 0.0, out);
      } else if (near(child, p)) {
        near_source(c, p, n, weight, out);
      } else {
        strata_source(c, p, n, weight, out);
      }
    }
  }
};

// With a view, the vertices of the elements it sees (straight or through
// mirrors and glass); the rest are not in the picture and keep the element
// solution. Without one (empty), every vertex.
std::vector<bool> vertices_to_gather(const hierarchical_solver& solver) {
  if (solver.view.seen.empty()) return {};
  const patch_mesh& mesh = solver.mesh();
  std::vector<bool> wanted(mesh.vertex_count(), false);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    if (solver.view.seen[std::size_t(solver.meshes.input_element[e])] > 0.0)
      for (int k = 0; k < 3; ++k) wanted[std::size_t(mesh.elements[e][k])] = true;
  return wanted;
}

// final_gather_cost over the vertices `wanted` (empty: all of them).
std::uint64_t gather_cost(const hierarchical_solver& solver, const std::vector<bool>& wanted) {
  // Per vertex, the links above the element around it with the most:
  // a vertex gathers at least those, and its other elements' chains share
  // all but their lowest nodes with it. Counted without building the
  // vertices' node lists, which the gather builds once.
  const link_hierarchy& h = solver.hierarchy;
  const cluster_tree& tree = h.tree;
  const patch_mesh& mesh = solver.mesh();
  std::vector<std::uint64_t> chain(tree.nodes.size(), 0);
  for (std::size_t i = 0; i < tree.nodes.size(); ++i)
    chain[i] =
        h.links.count_of(i) + h.mirror_links.count_of(i) + (i > 0 ? chain[std::size_t(tree.nodes[i].parent)] : 0);
  std::vector<std::uint64_t> most(mesh.vertex_count(), 0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) {
      std::uint64_t& m = most[std::size_t(mesh.elements[e][k])];
      m = std::max(m, chain[std::size_t(tree.leaf_of_element[e])]);
    }
  std::uint64_t total = 0;
  for (std::size_t v = 0; v < most.size(); ++v)
    if (wanted.empty() || wanted[v]) total += most[v];
  return total;
}

}  // namespace

std::uint64_t final_gather_cost(const hierarchical_solver& solver) {
  return gather_cost(solver, vertices_to_gather(solver));
}

bool final_gather(hierarchical_solver& solver) {
  std::vector<bool> wanted = vertices_to_gather(solver);
  if (gather_cost(solver, wanted) > solver.params.gather_budget) return false;
  const link_hierarchy& h = solver.hierarchy;
  const cluster_tree& tree = h.tree;
  const patch_mesh& mesh = solver.mesh();
  const scene& s = *solver.source;
  std::vector<rgb> node_b(tree.nodes.size()), node_e(tree.nodes.size());
  std::vector<std::array<rgb, 6>> sent_b, sent_e;
  pull(solver, solver.light.total, node_b, &sent_b);
  pull(solver, solver.sources.emission, node_e, &sent_e);
  // Per link from an inner node: its strata estimate over the disc
  // estimate at its receiver's centre; untrusted (-1) where they differ by
  // more than correction_trust, and the strata estimate is then made at
  // each vertex.
  // (Closed scenes' links from non-emitting sources carry the disc
  // estimate itself: kept_factor.)
  std::vector<float> correction(h.links.size(), 1.0f);
  for_each_block(solver.params.parallel, h.links.size(), 4096, [&](std::size_t b, std::size_t end) {
    for (std::size_t l = b; l < end; ++l) {
      const hierarchy_link& link = h.links.links[l];
      const cluster_node& r = tree.nodes[std::size_t(link.receiver)];
      const cluster_node& src = tree.nodes[std::size_t(link.source)];
      if (src.leaf() || !r.oriented) continue;
      if (solver.progress.closed && !node_emits(node_e, link.source)) continue;
      const double at_centre = disc_factor(src, r.centroid, &r.normal);
      const double ratio = at_centre > 0.0 ? double(link.factor) / at_centre : INFINITY;
      const bool trusted = ratio <= correction_trust && ratio * correction_trust >= 1.0;
      correction[l] = trusted ? float(ratio) : -1.0f;
    }
  });
  const vertex_elements around = elements_around_vertices(mesh);
  // A point in a source element's plane sees it edge-on: its own elements
  // and flat neighbours, which round-off would put a hair in front.
  const gather_inputs inputs{solver, node_b, node_e, sent_b, sent_e, 1e-9 * mesh.scene_diagonal};
  const bool lamps = has_lights_beyond_surfaces(s);
  const std::size_t n = mesh.vertex_count();
  solver.gathered_at = std::move(wanted);
  const std::vector<bool>& at = solver.gathered_at;
  light_parts& out = solver.gathered;
  out.total.assign(n, rgb(0.0));
  out.direct.assign(n, rgb(0.0));
  out.mirrored.assign(n, rgb(0.0));
  std::atomic<std::uint64_t> evaluations{0}, rays{0};
  for_each_block(solver.params.parallel, n, 256, [&](std::size_t b, std::size_t end) {
    std::uint64_t count = 0, lamp_rays = 0;
    std::vector<std::pair<int, double>> nodes;
    for (std::size_t v = b; v < end; ++v) {
      if (!at.empty() && !at[v]) continue;
      nodes_above(solver, around, v, nodes);
      const vec3& p = mesh.receive_points[v];
      const vec3& normal = mesh.normals[v];
      gathered_sum plain, emitted;
      rgb mirrored(0.0), mirrored_direct(0.0);
      for (const auto& [a, share] : nodes) {
        for (std::size_t l = h.links.offsets[std::size_t(a)]; l < h.links.offsets[std::size_t(a) + 1]; ++l) {
          const hierarchy_link& link = h.links.links[l];
          const cluster_node& src = tree.nodes[std::size_t(link.source)];
          const bool emits = node_emits(node_e, link.source);
          // A partly visible link's visibility is the mean over its
          // receiver; the vertex casts its own rays, so a shadow edge across
          // a coarse link shows at the vertices it passes between.
          double visibility = double(link.visibility);
          if (visibility > 0.0 && visibility < 1.0) {
            const int point_rays = emits ? solver.params.gather_emitter_rays : solver.params.gather_partial_rays;
            if (point_rays > 0) visibility = point_visibility(solver, p, normal, link.source, point_rays, lamp_rays);
          }
          const double weight = share * visibility;
          gathered_sum& into = emits ? emitted : plain;
          ++count;
          if (!(weight > 0.0)) continue;
          if (src.leaf()) {
            const double f = inputs.leaf_factor(src, p, normal);
            if (f > 0.0) inputs.add(link.source, weight * f, vec3(0.0), 0.0, into);
          } else if (near(src, p)) {
            inputs.near_source(link.source, p, normal, weight, into);
          } else if (correction[l] < 0.0f) {
            inputs.strata_source(link.source, p, normal, weight, into);
          } else {
            vec3 towards;
            double send = 0.0;
            const double f = std::min(1.0, disc_factor(src, p, &normal, towards, send) * double(correction[l]));
            if (f > 0.0) inputs.add(link.source, weight * f, -towards, send, into);
          }
        }
        for (const mirror_link& m : h.mirror_links.of(std::size_t(a))) {
          const mirror_chain& chain = h.chains[std::size_t(m.chain)];
          const cluster_node& src = tree.nodes[std::size_t(m.link.source)];
          ++count;
          vec3 dir;
          double send = 0.0;
          double f = disc_factor(src, p, &normal, dir, send, &chain);
          if (dir == vec3(0.0)) continue;  // no direction
          const vec3 from = chain.source_direction(-dir);
          if (src.leaf()) {
            std::array<vec3, 3> polygon = element_corners(mesh, std::size_t(src.element));
            for (vec3& corner : polygon) corner = chain.image(corner);
            f = point_polygon_form_factor(p, normal, polygon);
          }
          f *= share * double(m.link.visibility);
          if (!(f > 0.0)) continue;
          mirrored += f * chain.path.kr * sent_radiosity(solver, node_b, sent_b, m.link.source, from, send);
          mirrored_direct += f * chain.path.kr * sent_radiosity(solver, node_e, sent_e, m.link.source, from, send);
        }
      }
      // The normaliser is for the plain links alone: a mirror's solid
      // angle is counted once, by the links to the mirror itself. In a
      // closed scene the emitters' links are taken as they are, and the
      // others make up the rest of the vertex's form-factor sum
      // (closed_scene.h).
      const closed_scale scale =
          solver.progress.closed ? closed_scale_for(emitted.factors, plain.factors) : closed_scale{};
      const rgb rho = mesh.vertex_rho[v];
      const rgb lamp = lamps ? point_light_irradiance(s, solver.context, p, normal, lamp_rays) : rgb(0.0);
      const std::vector<light_image>& images = solver.sources.light_images;
      const rgb lamp_images =
          images.empty() ? rgb(0.0) : mirrored_light_irradiance(solver.context, images, p, normal, lamp_rays);
      out.total[v] = rho * (plain.b * scale.rest + emitted.b * scale.emitters + mirrored + lamp + lamp_images);
      out.direct[v] = rho * (plain.e * scale.rest + emitted.e * scale.emitters + lamp);
      out.mirrored[v] = rho * (mirrored_direct + lamp_images);
    }
    evaluations += count;
    rays += lamp_rays;
  });
  solver.progress.gather_evaluations += evaluations.load();
  solver.progress.rays += rays.load();
  return true;
}

}  // namespace bounce
