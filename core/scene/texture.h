// Texture lookups: what a material's texture does to its diffuse
// reflectance, rho(x) = rho * texture_value(t, uv).
#pragma once

#include <vector>

#include "scene/scene.h"

namespace bounce {

// Linear RGB of the texture at (u, v). Images repeat outside [0, 1] and are
// filtered bilinearly; v = 1 is the image's top row. Checkers alternate
// color0/color1 over `scale` squares per unit of uv, color0 at the origin.
rgb texture_value(const texture& t, const vec2& uv);

// Coverage of the texture at (u, v), filtered as texture_value: its alpha
// channel, or 1 where it has none.
double texture_alpha(const texture& t, const vec2& uv);

// Whether material `m` (its texture in `textures`) has no surface at
// (u, v): a cut-out's hole.
bool cut_out(const material& m, const std::vector<texture>& textures, const vec2& uv);

// Mean value of a texture over its whole domain (how a texture scales rho
// in the radiosity pass; the ray tracer puts the detail back per pixel).
rgb texture_mean(const texture& t);

}  // namespace bounce
