// Views of the hierarchical solver for tests and the panel: where its
// links are, and the element-level solution it converges to.
#pragma once

#include <vector>

#include "radiosity/hierarchical/state.h"

namespace bounce {

// Links per receiving element: every link whose receiver holds the element
// counts, spread by area (links per unit area).
std::vector<double> link_density(const hierarchical_solver& solver);

// The element-level solution: every element gathers from every element,
// with the leaf-to-leaf form factor and visibility the oracle would give
// (the same rays), normalised the same way, solved densely. Small scenes
// only (at most 4,000 elements).
std::vector<rgb> element_level_solution(const hierarchical_solver& solver);

}  // namespace bounce
