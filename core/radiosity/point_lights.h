// Direct light from point lights at every vertex, with shadow rays: what
// both solvers take as the lights' contribution (B = rho * I cos / r^2).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/patch_mesh.h"
#include "radiosity/form_factor.h"

namespace bounce {

// Irradiance the point lights give a point facing `n` (shadow rays
// included); counts the rays cast in `rays`.
rgb point_light_irradiance(const scene& s, const form_factor_context& context, const vec3& p, const vec3& n,
                           std::uint64_t& rays);

// Radiosity each vertex reflects of the point lights' direct light, for the
// vertices from `first` on (those before are left 0: adaptive refinement
// asks for its new vertices only). Adds the shadow rays cast to `rays`.
std::vector<rgb> point_light_radiosity(const scene& s, const patch_mesh& mesh, const form_factor_context& context,
                                       std::uint64_t& rays, std::size_t first = 0);

}  // namespace bounce
