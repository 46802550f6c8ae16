// What the hierarchical solver shows: its element solution at the
// vertices. Once the final links are solved (and the passes through
// mirrors and glass made), each element's light comes from the final
// gather; before, from the element solution as it stands.
#pragma once

#include <vector>

#include "radiosity/hierarchical/state.h"

namespace bounce {

// Per vertex: the area-weighted mean of the elements around it.
std::vector<rgb> element_to_vertex(const patch_mesh& mesh, const std::vector<rgb>& per_element);

// The solution per vertex of solver.mesh(): all of it, its direct part,
// and its caustic part (the lamp's part by way of mirrors and glass plus
// what mirror links bring from the emitters; empty when the scene has
// neither). Makes the final gather when it is due.
struct vertex_light {
  std::vector<rgb> radiosity, direct, caustic;
};
vertex_light publish_vertex_light(hierarchical_solver& solver);

// Whether the discretisation and the right-hand side are final: the
// residual then measures what is left to solve.
bool solution_final(const hierarchical_solver& solver);

}  // namespace bounce
