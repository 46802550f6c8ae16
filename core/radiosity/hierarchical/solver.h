// Hierarchical radiosity with clustering (Hanrahan, Salzman & Aupperle
// 1991; Smits, Arvo & Greenberg 1994; Sillion 1995): the default solver.
//
// Unknowns: one radiosity per element (piecewise constant), published to
// the vertices as the area-weighted mean of the elements around each one.
// Nodes of the cluster tree (cluster_tree.h) exchange light through links
// (link_table.h), which the oracle (oracle.h) makes from the root's
// self-link down, splitting pairs while they would carry more than the
// tolerance unrefined (link_refinement.h). The system B = E + K B, with K
// the gather and push-pull over the links (transport.h), is solved with
// BiCGSTAB (iteration.h); between blocks of iterations the links are
// refined with the tolerance lowered, against the solution found so far,
// and elements that leaf links need finer are split below the input mesh
// (element_refinement.h). Light through planar mirrors travels on links
// through mirror chains; through curved mirrors and glass by passes into
// the right-hand side (specular_passes.h). Closed scenes are normalised
// (closed_scene.h). Once everything is final, a final gather evaluates
// every link at each element (final_gather.h).
//
// The file layout follows those concepts; this file is the state machine
// that drives them, one step at a time.
#pragma once

#include <memory>

#include "radiosity/hierarchical/state.h"

namespace bounce {

// Builds the tree, finds whether the scene is closed, traces the
// emitters' light through mirrors and glass, and gives the point lights'
// direct light to every element. Links come with the first step.
std::unique_ptr<hierarchical_solver> make_hierarchical_solver(const scene& s, const patch_mesh& mesh,
                                                              const form_factor_context& context,
                                                              const hierarchical_params& params);

// Back to B = E + lamp on the input mesh, with no links.
void restart_hierarchical(hierarchical_solver& solver);

// One step: the first makes the coarsest links and one Jacobi sweep (the
// direct light everywhere); the next run a block of BiCGSTAB iterations,
// and refine the links (and split elements) once the residual is below
// `refine_below` (a fraction of the emitted power) or stalls, until the
// tolerance is final; then the passes of light through mirrors and glass.
// Returns false when there is nothing left to improve.
bool step_hierarchical(hierarchical_solver& solver, double refine_below);

// Whether the links are final and no element is still to be split: the
// solution's discretisation will not change any more.
bool refinement_done(const hierarchical_solver& solver);

}  // namespace bounce
