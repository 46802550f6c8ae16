// Form-factor kernels from a point to a node of the cluster tree: what the
// oracle estimates a link with, what a kept link carries, and what the
// final gather evaluates at each element.
//
// The disc estimate treats the node as a disc of its projected area
// towards the point, at its centroid, facing the point: F = A / (pi r^2 +
// A), finite as r goes to 0. It misses by the second order of the
// source's angular size, in a box nearly always the same way (short), so
// kept links from inner nodes carry the strata estimate instead: the exact
// factors of the node's sample elements (Lambert's formula), each standing
// for its share of the node's area.
#pragma once

#include "mesh/patch_mesh.h"
#include "radiosity/hierarchical/cluster_tree.h"
#include "radiosity/hierarchical/mirror_chains.h"

namespace bounce {

// The disc estimate from point p to node s: times the cosine at p when p
// has a normal n (a cluster receiver has none: per unit area facing the
// source). `towards` is set to the unit direction from p to s (0 when p is
// at the centroid), and `send` to s's projected area towards p. Through a
// mirror chain (not null), the same to s's image.
double disc_factor(const cluster_node& s, const vec3& p, const vec3* n, vec3& towards, double& send,
                   const mirror_chain* chain = nullptr);
double disc_factor(const cluster_node& s, const vec3& p, const vec3* n, const mirror_chain* chain = nullptr);

// The strata estimate from point p (normal n) to inner node s. Sample
// elements that look small from p take the point-to-point kernel at their
// centre (within well under 1% of Lambert's formula, at a tenth of its
// cost). At most 1.
double strata_factor(const cluster_tree& tree, const patch_mesh& mesh, int s, const vec3& p, const vec3& n);

// How much the form factor from oriented node r to node s varies over r:
// max - min of the kernel (Lambert's formula to a leaf, the disc estimate
// to an inner node) at r's centroid and its sample elements' centroids.
double factor_variation(const cluster_tree& tree, const patch_mesh& mesh, int r, int s);

}  // namespace bounce
