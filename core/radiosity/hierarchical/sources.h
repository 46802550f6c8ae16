// What follows from the mesh being solved: per element rho, E and the
// point lights' reflected light (the right-hand side), the emitted power,
// and the operator's working arrays sized to the tree.
#pragma once

#include <vector>

#include "radiosity/hierarchical/state.h"

namespace bounce {

// Takes `tree` (built over solver.meshes.current) and remakes everything
// that depends on the mesh: cube slots and buffers for the tree, rho, E,
// lamp (the point lights' light, plus sources.specular_lamp as it stands)
// and the emitted power. Drops the links and the split requests; leaves
// the solution to the caller.
void rebuild_for_mesh(hierarchical_solver& solver, cluster_tree tree);

// E + lamp per element: the system's right-hand side.
std::vector<rgb> right_hand_side(const hierarchical_solver& solver);

// The lamp's direct part at element e: the point lights straight, not by
// way of mirrors and glass.
rgb direct_lamp(const hierarchical_solver& solver, std::size_t e);

}  // namespace bounce
