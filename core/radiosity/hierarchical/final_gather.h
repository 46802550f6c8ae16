// The final gather, made at the vertices: once the final links are
// solved, each vertex gathers over the links of the elements around it
// (and their ancestors) with the kernel evaluated at the vertex itself,
// rather than taking the mean of its elements' values. A vertex is what
// the Gouraud view interpolates, so corners, contacts and the edges of
// light get point values instead of smeared ones.
//
// Each element's chain of links (its leaf and the ancestors) sees every
// source once; a vertex takes the area-weighted mean of its elements'
// chains, so a link of an ancestor that all of them share counts once,
// with weight 1. Sources that are elements: Lambert's formula at the
// vertex's receive point (a hair inside the surface at a boundary vertex:
// the one-sided limit where the kernel is singular, as the progressive
// solver gathers). Inner nodes: the disc estimate at the vertex, corrected
// as the link's strata estimate corrects it at its receiver's centre (the
// correction is the source's shape, which changes slowly over a receiver
// that the oracle kept small against the distance). Through mirror
// chains: the kernel to the source's image. Point lights: at the vertex,
// with their shadow rays.
#pragma once

#include <cstdint>

#include "radiosity/hierarchical/state.h"

namespace bounce {

// The kernel evaluations a final gather costs, about: over vertices, the
// links above the element around each that has the most (a lower bound:
// the gather also takes the other elements' lowest links).
std::uint64_t final_gather_cost(const hierarchical_solver& solver);

// Fills solver.gathered with each vertex's reflected light (total: from
// the solution; direct: from the emitters and point lights alone over
// plain links; mirrored: from the emitters through mirror links),
// normalised like the operator. Past params.gather_budget it is not made
// and returns false.
bool final_gather(hierarchical_solver& solver);

}  // namespace bounce
