// Closed scenes: every element's form factors must sum to 1. The
// estimates of coarse links do not quite, and at rho = 0.999 an error of
// 1e-4 in the sum is 10% in B. Where the scene is closed (no sampled ray
// escapes it), each element's gathered irradiance through the plain links
// is divided by its form-factor sum.
#pragma once

#include <vector>

#include "image/tonemap.h"
#include "radiosity/hierarchical/state.h"

namespace bounce {

// Whether cosine-distributed rays from a sample of the elements (up to
// 4096 of them, 8 rays each) all stay inside the scene.
bool scene_is_closed(const hierarchical_solver& solver);

// Whether tree node `node` emits, by the emission pulled to the nodes: the
// links from it are the normaliser's emitter links, and carry the strata
// estimate in closed scenes too.
inline bool node_emits(const std::vector<rgb>& node_e, int node) {
  return luminance(node_e[std::size_t(node)]) > 0.0;
}

// The scale that brings form-factor sums `emitters` (over the links from
// emitting sources) and `rest` (the other plain links) to 1: the links
// from emitters are taken as they are and the rest make up the shortfall,
// unless there is no rest or the emitters alone reach 1 (a furnace, where
// everything emits): then all alike.
closed_scale closed_scale_for(double emitters, double rest);

// hierarchy.normalizer and hierarchy.emitter_links: each element's
// closed_scale_for its sums when progress.closed, else 1 and no emitter
// links. Made after every link refinement; node_e: the emission pulled to
// the nodes.
void update_normalizer(hierarchical_solver& solver, const std::vector<rgb>& node_e);

}  // namespace bounce
