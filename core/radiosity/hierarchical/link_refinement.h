// Link refinement: the oracle (oracle.h) applied from the root's
// self-link down, or to every existing link against the solution found so
// far. Pairs the oracle splits are divided on their larger side (large
// pairs fan out over the threads); pairs it keeps become links; leaf pairs
// it keeps may mark their receiving element for splitting
// (element_refinement.h). Links through chains of planar mirrors are made
// afresh from (root, root) for every chain at every refinement: they are
// few, and a pair that no ray passed at a coarse tolerance may matter at a
// finer one.
#pragma once

#include "radiosity/hierarchical/state.h"

namespace bounce {

// Refines every link against the current solution at `tolerance` (a
// fraction of the power leaving all surfaces, at least the emitted power),
// or makes the first links when there are none; remakes the links through
// mirrors, the split marks and the closed-scene normaliser. Past
// params.max_links no pair is split further and progress.warning says so;
// past solver.deadline neither, and progress.links_cut_short says so (the
// links are then not final).
void refine_links(hierarchical_solver& solver, double tolerance);

}  // namespace bounce
