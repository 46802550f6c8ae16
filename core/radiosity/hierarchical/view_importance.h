// Importance from the camera (Smits, Arvo & Salesin 1992): the view leads
// the refinement. The camera's rays give each element how densely the
// picture sees it, R (rays per unit area, through mirrors and glass); the
// importance leaving a surface, W = rho R + K W, is the radiosity system
// with rho R for emission (the kernel is symmetric), solved by a few
// sweeps over the links as they stand; what a receiver passes on to the
// picture per unit of irradiance is Y = R + (K W) / rho. A link i <- j
// changes the picture by F B_j A_i Y_i, and the picture's reflected light
// is V = sum A (Y - R) (E + lamp) (emitters seen straight need no link):
// the oracle compares F B A with the tolerance as before, with each
// receiver's charge weighed by Y_i x emitted power / V. Seen evenly, Y is
// even and the weight about 1;
// what the camera cannot see, even by way of other surfaces, weighs 0 and
// stays coarse, so the part in view is refined as if it were the scene.
#pragma once

#include <optional>
#include <vector>

#include "radiosity/hierarchical/state.h"

namespace bounce {

// Per element of `mesh`: the camera's rays (about rays_across x
// rays_across over the picture) that reach it, straight or through up to
// four mirror and glass bounces weighted by kr and kt, per unit area; the
// same whether the rays run on TBB's threads (`parallel`) or not.
std::vector<double> seen_density(const patch_mesh& mesh, const scene& s, const form_factor_context& context,
                                 const camera& view, int rays_across, bool parallel);

// Leads the solver's refinement by `view` from now on, or by no view
// (every part of the scene alike): the links and elements already refined
// stay, and the next step refines again at the current tolerance.
void set_view(hierarchical_solver& solver, const std::optional<camera>& view);

// Remakes the receivers' weights (view_weights::node) from the seen
// density and the links as they stand; with no view, or no links yet, or
// a view that sees no light, the weights are left empty (every receiver
// weighs 1).
void update_view_weights(hierarchical_solver& solver);

// What the oracle multiplies receiver `node`'s charge by: 1 without a view.
inline double receiver_weight(const hierarchical_solver& solver, int node) {
  return solver.view.node.empty() ? 1.0 : solver.view.node[std::size_t(node)];
}

}  // namespace bounce
