#include "radiosity/cluster_tree.h"

#include <algorithm>
#include <cmath>
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
  node.centroid = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
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

}  // namespace

cluster_tree build_cluster_tree(const patch_mesh& mesh) {
  cluster_tree tree;
  const std::size_t n = mesh.element_count();
  tree.leaf_of_element.assign(n, -1);
  if (n == 0) return tree;
  std::vector<vec3> centroid(n);
  for (std::size_t e = 0; e < n; ++e) {
    const glm::ivec3 t = mesh.elements[e];
    centroid[e] = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  tree.nodes.reserve(2 * n);
  tree.nodes.emplace_back();

  // Top-down, breadth first: a node's two children are appended together,
  // so they are consecutive and come after their parent.
  struct range {
    int node;
    std::size_t begin, end;
    int depth;
  };
  std::vector<range> pending{{0, 0, n, 0}};
  for (std::size_t next = 0; next < pending.size(); ++next) {
    const range r = pending[next];
    if (int(tree.levels.size()) == r.depth) tree.levels.push_back(r.node);
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
    pending.push_back({first, r.begin, middle, r.depth + 1});
    pending.push_back({first + 1, middle, r.end, r.depth + 1});
  }
  tree.levels.push_back(int(tree.nodes.size()));
  // Bottom-up: children have larger indices than their parent.
  for (int i = int(tree.nodes.size()) - 1; i >= 0; --i)
    if (!tree.nodes[i].leaf()) fill_inner(tree, i);
  // Strata bottom-up: slice k of a node covers area fraction
  // [k, k + 1) / K; its centre falls in one child, whose slice at the same
  // relative position supplies the element.
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
  return tree;
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
