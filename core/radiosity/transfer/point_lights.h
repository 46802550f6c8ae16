// Direct light that does not come from the surfaces, with shadow rays:
// punctual lights (B = rho * I cos / r^2 for points and spots, with the
// spot's cone; rho * E cos for a sun) and the sky (64 stratified,
// cosine-weighted rays to it). What all solvers take as its contribution.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/patch_mesh.h"
#include "radiosity/transfer/form_factor.h"

namespace bounce {

// Irradiance the punctual lights and the sky give a point facing `n` (shadow
// rays included); counts the rays cast in `rays`.
rgb point_light_irradiance(const scene& s, const form_factor_context& context, const vec3& p, const vec3& n,
                           std::uint64_t& rays);

// The punctual lights' part alone (no sky): what changes sharply over a
// surface, at a spot's edge and a point light's or sun's shadow.
rgb punctual_light_irradiance(const scene& s, const form_factor_context& context, const vec3& p, const vec3& n,
                              std::uint64_t& rays);

// Radiosity each vertex reflects of that direct light, for the
// vertices from `first` on (those before are left 0: adaptive refinement
// asks for its new vertices only). Adds the shadow rays cast to `rays`.
std::vector<rgb> point_light_radiosity(const scene& s, const patch_mesh& mesh, const form_factor_context& context,
                                       std::uint64_t& rays, std::size_t first = 0);

}  // namespace bounce
