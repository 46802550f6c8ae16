#include "radiosity/hierarchical/cluster_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace bounce {
namespace {

// Two elements face the same way when their normals differ by less than
// about 1e-3 rad.
constexpr double same_direction = 1.0 - 5e-7;

void fill_leaf(cluster_node& node, const patch_mesh& mesh, int element) {
  const glm::ivec3 t = mesh.elements[element];
  node.element = element;
  node.elements = 1;
  node.area = mesh.element_areas[element];
  node.centroid = element_centroid(mesh, std::size_t(element));
  node.lo = glm::min(glm::min(mesh.positions[t[0]], mesh.positions[t[1]]), mesh.positions[t[2]]);
  node.hi = glm::max(glm::max(mesh.positions[t[0]], mesh.positions[t[1]]), mesh.positions[t[2]]);
  node.oriented = true;
  node.normal = mesh.element_normals[element];
  for (int k = 0; k < 3; ++k) {
    node.projected[2 * k] = node.area * std::max(0.0, node.normal[k]);
    node.projected[2 * k + 1] = node.area * std::max(0.0, -node.normal[k]);
  }
}

void fill_inner(cluster_tree& tree, int index) {
  cluster_node& node = tree.nodes[index];
  node.area = 0.0;
  node.elements = 0;
  node.centroid = vec3(0.0);
  node.projected = {};
  node.lo = vec3(std::numeric_limits<double>::max());
  node.hi = vec3(-std::numeric_limits<double>::max());
  node.oriented = true;
  const vec3 first_normal = tree.nodes[node.first_child].normal;
  for (int c = node.first_child; c < node.first_child + node.child_count; ++c) {
    const cluster_node& child = tree.nodes[c];
    node.area += child.area;
    node.elements += child.elements;
    node.centroid += child.centroid * child.area;
    node.lo = glm::min(node.lo, child.lo);
    node.hi = glm::max(node.hi, child.hi);
    for (int k = 0; k < 6; ++k) node.projected[k] += child.projected[k];
    node.oriented = node.oriented && child.oriented && glm::dot(child.normal, first_normal) > same_direction;
  }
  node.centroid = node.area > 0.0 ? node.centroid / node.area : 0.5 * (node.lo + node.hi);
  node.normal = node.oriented ? first_normal : vec3(0.0);
}

// Grows a tree top-down, breadth first: a node's children are appended
// together, so they are consecutive and come after their parent. A node
// either copies the shape of an old tree's node (extend_cluster_tree) or
// splits a range of `order` at the median along the widest axis of the
// centroids; an old leaf continues as the range of its element's pieces.
struct tree_builder {
  const patch_mesh& mesh;
  const cluster_tree* old = nullptr;
  std::vector<std::size_t> piece_start;  // old element o's pieces are order[piece_start[o], piece_start[o + 1])
  std::vector<int> order;
  std::vector<vec3> centroid;

  struct pending_node {
    int node;
    int old_node;  // -1: a range of order
    std::size_t begin, end;
    int depth;
    bool piece = false;  // under a split element
  };

  explicit tree_builder(const patch_mesh& m) : mesh(m) {
    const std::size_t n = mesh.element_count();
    centroid.resize(n);
    for (std::size_t e = 0; e < n; ++e) centroid[e] = element_centroid(mesh, e);
  }

  cluster_tree build(pending_node root, std::vector<int>* node_of_old) {
    cluster_tree tree;
    tree.leaf_of_element.assign(mesh.element_count(), -1);
    if (mesh.element_count() == 0) return tree;
    tree.nodes.reserve(2 * mesh.element_count());
    tree.nodes.emplace_back();
    std::vector<pending_node> pending{root};
    for (std::size_t next = 0; next < pending.size(); ++next) {
      pending_node r = pending[next];
      if (int(tree.levels.size()) == r.depth) tree.levels.push_back(r.node);
      if (r.old_node >= 0) {
        (*node_of_old)[std::size_t(r.old_node)] = r.node;
        const cluster_node& o = old->nodes[std::size_t(r.old_node)];
        r.piece = o.piece;
        if (!o.leaf()) {
          const int first = int(tree.nodes.size());
          tree.nodes.resize(tree.nodes.size() + std::size_t(o.child_count));
          tree.nodes[r.node].first_child = first;
          tree.nodes[r.node].child_count = o.child_count;
          for (int c = 0; c < o.child_count; ++c) {
            tree.nodes[first + c].parent = r.node;
            pending.push_back({first + c, o.first_child + c, 0, 0, r.depth + 1});
          }
          continue;
        }
        r.begin = piece_start[std::size_t(o.element)];
        r.end = piece_start[std::size_t(o.element) + 1];
        r.piece = r.piece || r.end - r.begin > 1;
      }
      tree.nodes[r.node].piece = r.piece;
      if (r.end - r.begin == 1) {
        fill_leaf(tree.nodes[r.node], mesh, order[r.begin]);
        tree.leaf_of_element[order[r.begin]] = r.node;
        continue;
      }
      vec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
      for (std::size_t i = r.begin; i < r.end; ++i) {
        lo = glm::min(lo, centroid[order[i]]);
        hi = glm::max(hi, centroid[order[i]]);
      }
      const vec3 extent = hi - lo;
      const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
      const std::size_t middle = r.begin + (r.end - r.begin) / 2;
      std::nth_element(order.begin() + std::ptrdiff_t(r.begin), order.begin() + std::ptrdiff_t(middle),
                       order.begin() + std::ptrdiff_t(r.end),
                       [&](int a, int b) { return centroid[a][axis] < centroid[b][axis]; });
      const int first = int(tree.nodes.size());
      tree.nodes.emplace_back();
      tree.nodes.emplace_back();
      tree.nodes[r.node].first_child = first;
      tree.nodes[r.node].child_count = 2;
      tree.nodes[first].parent = tree.nodes[first + 1].parent = r.node;
      pending.push_back({first, -1, r.begin, middle, r.depth + 1, r.piece});
      pending.push_back({first + 1, -1, middle, r.end, r.depth + 1, r.piece});
    }
    tree.levels.push_back(int(tree.nodes.size()));
    finish(tree);
    return tree;
  }

  // Bottom-up (children have larger indices than their parent): the inner
  // nodes' sums, then the strata.
  static void finish(cluster_tree& tree) {
    for (int i = int(tree.nodes.size()) - 1; i >= 0; --i)
      if (!tree.nodes[i].leaf()) fill_inner(tree, i);
    // Slice k of a node covers area fraction [k, k + 1) / K; its centre
    // falls in one child, whose slice at the same relative position
    // supplies the element.
    constexpr int strata = cluster_tree::sample_strata;
    tree.strata.resize(tree.nodes.size());
    for (int i = int(tree.nodes.size()) - 1; i >= 0; --i) {
      const cluster_node& node = tree.nodes[i];
      tree.oriented_nodes += node.oriented ? 1 : 0;
      if (node.leaf()) {
        tree.strata[i].fill(node.element);
        continue;
      }
      for (int k = 0; k < strata; ++k) {
        double position = (k + 0.5) / strata * node.area;
        int chosen = node.first_child + node.child_count - 1;
        for (int c = node.first_child; c < node.first_child + node.child_count; ++c) {
          if (position < tree.nodes[c].area || c == chosen) {
            chosen = c;
            break;
          }
          position -= tree.nodes[c].area;
        }
        const double area = tree.nodes[chosen].area;
        const int slice = area > 0.0 ? std::clamp(int(position / area * strata), 0, strata - 1) : 0;
        tree.strata[i][k] = tree.strata[chosen][slice];
      }
    }
  }
};

}  // namespace

cluster_tree build_cluster_tree(const patch_mesh& mesh) {
  tree_builder builder(mesh);
  builder.order.resize(mesh.element_count());
  std::iota(builder.order.begin(), builder.order.end(), 0);
  return builder.build({0, -1, 0, mesh.element_count(), 0}, nullptr);
}

cluster_tree extend_cluster_tree(const cluster_tree& old, const patch_mesh& mesh, std::span<const int> from,
                                 std::vector<int>& node_of_old) {
  tree_builder builder(mesh);
  builder.old = &old;
  // The pieces of each old element, together (a counting sort by `from`).
  const std::size_t old_elements = old.leaf_of_element.size();
  builder.piece_start.assign(old_elements + 1, 0);
  for (int o : from) ++builder.piece_start[std::size_t(o) + 1];
  for (std::size_t o = 0; o < old_elements; ++o) builder.piece_start[o + 1] += builder.piece_start[o];
  builder.order.resize(from.size());
  std::vector<std::size_t> fill(builder.piece_start.begin(), builder.piece_start.end() - 1);
  for (std::size_t e = 0; e < from.size(); ++e) builder.order[fill[std::size_t(from[e])]++] = int(e);
  node_of_old.assign(old.nodes.size(), -1);
  if (old.nodes.empty()) return build_cluster_tree(mesh);
  return builder.build({0, 0, 0, 0, 0}, &node_of_old);
}

double projected_area(const cluster_node& node, const vec3& d) {
  if (node.oriented) return node.area * std::max(0.0, glm::dot(node.normal, d));
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) sum += std::abs(d[k]) * node.projected[2 * k + (d[k] >= 0.0 ? 0 : 1)];
  return sum;
}

surface_point sample_node(const cluster_tree& tree, const patch_mesh& mesh, int index, double u, double v) {
  constexpr int strata = cluster_tree::sample_strata;
  const double scaled = u * strata;
  const int slice = std::clamp(int(scaled), 0, strata - 1);
  const int e = tree.strata[index][slice];
  u = std::clamp(scaled - slice, 0.0, std::nextafter(1.0, 0.0));
  const glm::ivec3 t = mesh.elements[e];
  // Uniform on the triangle (square-root warp).
  const double su = std::sqrt(u);
  const vec3 p =
      (1.0 - su) * mesh.positions[t[0]] + su * (1.0 - v) * mesh.positions[t[1]] + su * v * mesh.positions[t[2]];
  return {p, mesh.element_normals[e]};
}

}  // namespace bounce
