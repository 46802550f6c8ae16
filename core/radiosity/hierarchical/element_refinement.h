// Elements refined below the input mesh, lazily. An element-to-element
// pair cannot be split in the tree; where the light it carries matters
// and is partly shadowed or varies over the receiving element, that
// element is marked with the bisections that would bring the error under
// the tolerance (evenly lit elements never are). At the next link
// refinement the marked elements are bisected (Rivara's conforming
// longest-edge bisection, no element edge below min_edge), each becoming
// a node of the tree over its pieces and passing its radiosity to them;
// the links are then refined onto them. Elements end fine only where some
// link needs them: at contacts, shadow edges and gradients.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "radiosity/hierarchical/state.h"

namespace bounce {

// The bisections that the receiving element of leaf pair i <- j needs
// (0: none). The error of a constant per element is the variation of the
// transfer over it (the form factor towards its corners against the
// centre, times the source's radiosity and the element's area), or, on a
// shadow edge (partly visible), the whole transfer; each bisection halves
// it. Through a mirror chain (not null), the same with the source's image
// and kr. Off unless params.split_elements; never below min_edge
// (with a view and no min_edge given, a seen element may go below it).
int bisections_needed(const hierarchical_solver& solver, const std::vector<rgb>& node_b, double tolerance, int i, int j,
                      double factor, float visibility, const mirror_chain* chain);

// Marks (element, bisections) for the punctual lights' light, which no
// link carries: where it varies over an element (towards the corners
// against the centre, mirror images included) by more than the tolerance
// once times the element's area and rho: a spot's edge, a point light's or
// a sun's shadow. Each bisection halves the error, as for links. Empty
// unless params.split_elements and the scene has punctual lights. Adds
// the shadow rays cast to `rays`.
std::vector<std::pair<int, int>> lamp_marks(const hierarchical_solver& solver, double tolerance, std::uint64_t& rays);

// Element refinement still to make: marks, passes left, no failure.
bool splits_pending(const hierarchical_solver& solver);

// Bisects the marked elements (conforming, not below min_edge), carries
// the solution over (each piece keeps its element's), extends the tree
// with subtrees over the pieces (extend_cluster_tree: the links stay,
// renumbered; the next link refinement splits them onto the pieces) and
// remakes the per-element data. Returns false if nothing was split (with
// a warning if the mesh would grow past the mesher's limit).
bool split_marked_elements(hierarchical_solver& solver);

}  // namespace bounce
