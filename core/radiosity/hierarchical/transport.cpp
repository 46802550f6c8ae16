#include "radiosity/hierarchical/transport.h"

#include "base/check.h"
#include "base/parallel.h"

namespace bounce {
namespace {

// Irradiance on an oriented surface of normal n from six direction bins.
rgb from_bins(const std::array<rgb, 6>& bins, const vec3& n) {
  rgb sum(0.0);
  for (int k = 0; k < 3; ++k) sum += n[k] >= 0.0 ? n[k] * bins[2 * k] : -n[k] * bins[2 * k + 1];
  return sum;
}

// What one link brings its receiver: the source's radiosity towards the
// receiver (or its image's, through a mirror chain) times the factor and
// visibility, and the unit direction from the receiver to the source (or
// image), for cluster receivers' bins. False: no direction.
bool link_value(const hierarchical_solver& solver, const cluster_node& node, const hierarchy_link& link,
                const mirror_chain* chain, rgb& value, vec3& d) {
  const transport_buffers& buf = solver.buffers;
  const cluster_node& source = solver.hierarchy.tree.nodes[std::size_t(link.source)];
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

// The chain a link passes through (null for plain links).
const mirror_chain* chain_of(const hierarchical_solver&, const hierarchy_link&) {
  return nullptr;
}
const mirror_chain* chain_of(const hierarchical_solver& solver, const mirror_link& m) {
  return &solver.hierarchy.chains[std::size_t(m.chain)];
}

// Gather over one table of links (plain, or through mirrors) into their
// receivers, then push the irradiance down to the elements: out[e] =
// irradiance on element e. The pull is made beforehand.
template <typename link_type>
void gather_links(const hierarchical_solver& solver, const link_table<link_type>& table, std::vector<rgb>& out) {
  const link_hierarchy& h = solver.hierarchy;
  const cluster_tree& tree = h.tree;
  transport_buffers& buf = solver.buffers;
  const std::size_t n = tree.nodes.size();
  BOUNCE_DCHECK_EQ(table.offsets.size(), n + 1);
  BOUNCE_DCHECK_EQ(buf.gathered.size(), n);
  for_each_block(solver.params.parallel, n, 1024, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const cluster_node& node = tree.nodes[i];
      const int slot = h.cube_slot[i];
      rgb sum(0.0);
      std::array<rgb, 6> bins{};
      for (const link_type& l : table.of(i)) {
        const mirror_chain* chain = chain_of(solver, l);
        const hierarchy_link& link = link_of(l);
        if (!chain && slot < 0 && h.cube_slot[std::size_t(link.source)] < 0) {
          sum += double(link.factor) * double(link.visibility) * buf.node_b[std::size_t(link.source)];
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
        buf.bins[std::size_t(slot)] = bins;
    }
  });
  // Push, level by level: a cluster's bins accumulate down to the first
  // oriented node, which turns them into irradiance on its normal.
  for (std::size_t level = 1; level + 1 < tree.levels.size(); ++level) {
    const std::size_t begin = std::size_t(tree.levels[level]), end = std::size_t(tree.levels[level + 1]);
    for_each_block(solver.params.parallel, end - begin, 4096, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = begin + b; i < begin + e; ++i) {
        const int parent = tree.nodes[i].parent;
        const int slot = h.cube_slot[i], parent_slot = h.cube_slot[std::size_t(parent)];
        if (slot >= 0) {
          for (int k = 0; k < 6; ++k) buf.bins[std::size_t(slot)][k] += buf.bins[std::size_t(parent_slot)][k];
        } else {
          buf.gathered[i] += parent_slot >= 0 ? from_bins(buf.bins[std::size_t(parent_slot)], tree.nodes[i].normal)
                                              : buf.gathered[std::size_t(parent)];
        }
      }
    });
  }
  // A single-element mesh: the root is the leaf, and oriented.
  out.resize(solver.mesh().element_count());
  for_each_block(solver.params.parallel, out.size(), 4096, [&](std::size_t b, std::size_t e) {
    for (std::size_t el = b; el < e; ++el) out[el] = buf.gathered[std::size_t(tree.leaf_of_element[el])];
  });
}

}  // namespace

void pull(const hierarchical_solver& solver, const std::vector<rgb>& x, std::vector<rgb>& node_b,
          std::vector<std::array<rgb, 6>>* sent) {
  const cluster_tree& tree = solver.hierarchy.tree;
  const std::vector<int>& cube_slot = solver.hierarchy.cube_slot;
  BOUNCE_DCHECK_EQ(node_b.size(), tree.nodes.size());
  BOUNCE_DCHECK_EQ(x.size(), tree.leaf_of_element.size());
  if (sent) sent->resize(solver.buffers.bins.size());
  for (int level = int(tree.levels.size()) - 2; level >= 0; --level) {
    const std::size_t begin = std::size_t(tree.levels[std::size_t(level)]);
    const std::size_t end = std::size_t(tree.levels[std::size_t(level) + 1]);
    for_each_block(solver.params.parallel, end - begin, 4096, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = begin + b; i < begin + e; ++i) {
        const cluster_node& node = tree.nodes[i];
        if (node.leaf()) {
          node_b[i] = x[std::size_t(node.element)];
          continue;
        }
        rgb sum(0.0);
        for (int c = node.first_child; c < node.first_child + node.child_count; ++c)
          sum += node_b[std::size_t(c)] * tree.nodes[std::size_t(c)].area;
        node_b[i] = node.area > 0.0 ? sum / node.area : rgb(0.0);
        const int slot = cube_slot[i];
        if (!sent || slot < 0) continue;
        std::array<rgb, 6> out{};
        for (int c = node.first_child; c < node.first_child + node.child_count; ++c) {
          const cluster_node& child = tree.nodes[std::size_t(c)];
          if (const int child_slot = cube_slot[std::size_t(c)]; child_slot >= 0) {
            for (int k = 0; k < 6; ++k) out[k] += (*sent)[std::size_t(child_slot)][k];
          } else {
            for (int k = 0; k < 3; ++k)
              out[2 * k + (child.normal[k] >= 0.0 ? 0 : 1)] +=
                  node_b[std::size_t(c)] * (child.area * std::abs(child.normal[k]));
          }
        }
        (*sent)[std::size_t(slot)] = out;
      }
    });
  }
}

rgb sent_radiosity(const hierarchical_solver& solver, const std::vector<rgb>& node_b,
                   const std::vector<std::array<rgb, 6>>& sent, int source, const vec3& d, double area) {
  const int slot = solver.hierarchy.cube_slot[std::size_t(source)];
  if (slot < 0 || !(area > 0.0)) return node_b[std::size_t(source)];
  rgb sum(0.0);
  for (int k = 0; k < 3; ++k) sum += std::abs(d[k]) * sent[std::size_t(slot)][2 * k + (d[k] >= 0.0 ? 0 : 1)];
  return sum / area;
}

rgb sent_radiosity(const hierarchical_solver& solver, const std::vector<rgb>& node_b,
                   const std::vector<std::array<rgb, 6>>& sent, int source, const vec3& d) {
  if (solver.hierarchy.cube_slot[std::size_t(source)] < 0) return node_b[std::size_t(source)];
  return sent_radiosity(solver, node_b, sent, source, d,
                        projected_area(solver.hierarchy.tree.nodes[std::size_t(source)], d));
}

void gather_push(const hierarchical_solver& solver, const std::vector<rgb>& x, std::vector<rgb>& out,
                 std::vector<rgb>* mirrored, std::vector<rgb>* emitted) {
  transport_buffers& buf = solver.buffers;
  pull(solver, x, buf.node_b, &buf.sent);
  gather_links(solver, solver.hierarchy.links, out);
  if (emitted) {
    if (solver.hierarchy.emitter_links.empty())
      emitted->assign(out.size(), rgb(0.0));
    else
      gather_links(solver, solver.hierarchy.emitter_links, *emitted);
  }
  if (!mirrored) return;
  if (solver.hierarchy.mirror_links.empty()) {
    mirrored->assign(out.size(), rgb(0.0));
    return;
  }
  gather_links(solver, solver.hierarchy.mirror_links, *mirrored);
}

void apply_transport(const hierarchical_solver& solver, const std::vector<rgb>& x, std::vector<rgb>& out) {
  const link_hierarchy& h = solver.hierarchy;
  const bool mirrors = !h.mirror_links.empty();
  std::vector<rgb>& mirrored = solver.buffers.mirrored;
  std::vector<rgb>& emitted = solver.buffers.emitted;
  gather_push(solver, x, out, mirrors ? &mirrored : nullptr, &emitted);
  for_each_block(solver.params.parallel, out.size(), 16384, [&](std::size_t b, std::size_t end) {
    for (std::size_t e = b; e < end; ++e)
      out[e] = h.rho[e] * (normalised(out[e], emitted[e], h.normalizer[e]) + (mirrors ? mirrored[e] : rgb(0.0)));
  });
}

}  // namespace bounce
