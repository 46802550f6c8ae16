// The hierarchy of the hierarchical solver: a bounding-volume tree whose
// leaves are the mesh's elements and whose inner nodes are clusters of
// them (Smits, Arvo & Greenberg 1994; Sillion 1995). Low in the tree a
// node holds neighbouring elements of one flat surface (an "oriented"
// node, which receives and emits like one polygon); higher up it holds
// elements facing many ways (a cluster, which receives and emits by its
// projected area in each direction).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "mesh/patch_mesh.h"

namespace bounce {

struct cluster_node {
  int parent = -1;
  int first_child = -1;  // children are consecutive nodes
  int child_count = 0;
  int element = -1;  // a leaf: its element (every leaf is one element)
  int elements = 0;  // elements under it
  double area = 0.0;
  vec3 centroid{0.0};  // area-weighted centre of its elements
  vec3 lo{0.0}, hi{0.0};
  // Oriented nodes: every element faces `normal` (within 1e-3 rad).
  bool oriented = false;
  // Under an element split while solving (extend_cluster_tree): its pieces
  // exist for how the light varies over them, and are refined by that.
  bool piece = false;
  vec3 normal{0.0};
  // Members' area seen from the six axis directions +x, -x, +y, -y, +z, -z:
  // sum of area x max(0, +-n_k). A direction d sees about
  // sum_k |d_k| x projected[side of d_k][k] (exact for axis-aligned members).
  std::array<double, 6> projected{};

  bool leaf() const { return child_count == 0; }
  double radius() const { return 0.5 * glm::length(hi - lo); }
};

struct cluster_tree {
  std::vector<cluster_node> nodes;  // nodes[0] is the root; a parent comes before its children
  // Nodes are stored level by level: level d is [levels[d], levels[d + 1]).
  std::vector<int> levels;
  std::vector<int> leaf_of_element;
  std::size_t oriented_nodes = 0;
  // Per inner node, sample_strata elements drawn by area (stratified, the
  // k-th from the k-th slice of the node's area): what sample_node draws
  // its points from, without descending the tree.
  static constexpr int sample_strata = 8;
  std::vector<std::array<int, sample_strata>> strata;  // indexed by node; leaves hold their element
};

// Builds the tree over the mesh's elements (median splits along the widest
// axis of the centroids), children before grandchildren in index order.
cluster_tree build_cluster_tree(const patch_mesh& mesh);

// The tree of `mesh`, a refinement of the mesh `old` was built on
// (from[e]: the old element that element e lies in): every old node keeps
// its place in the shape (node_of_old maps old node indices to new ones),
// and an old leaf whose element was split becomes the root of a subtree
// over its pieces. Links between old nodes stay valid, renumbered.
cluster_tree extend_cluster_tree(const cluster_tree& old, const patch_mesh& mesh, std::span<const int> from,
                                 std::vector<int>& node_of_old);

// The area `node` shows towards unit direction d (emitting or receiving
// along d): exact for oriented nodes (area x max(0, n.d)), the six-axis
// estimate for clusters.
double projected_area(const cluster_node& node, const vec3& d);

// A point on the node's surface, drawn by area from two uniform numbers in
// [0, 1), with the normal of the element it lies on: u picks one of the
// node's strata elements (and, rescaled, the point in it with v).
struct surface_point {
  vec3 position{0.0};
  vec3 normal{0.0};
};
surface_point sample_node(const cluster_tree& tree, const patch_mesh& mesh, int node, double u, double v);

}  // namespace bounce
