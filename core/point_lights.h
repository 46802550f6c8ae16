// Direct light from point lights at every vertex, with shadow rays: what
// both solvers take as the lights' contribution (B = rho * I cos / r^2).
#pragma once

#include <cstdint>
#include <vector>

#include "form_factor.h"
#include "patch_mesh.h"

namespace bounce {

// Radiosity each vertex reflects of the point lights' direct light.
// Adds the shadow rays cast to `rays`.
std::vector<rgb> point_light_radiosity(const scene& s, const patch_mesh& mesh, const form_factor_context& context,
                                       std::uint64_t& rays);

}  // namespace bounce
