// Display encoding shared by every picture Bounce writes: linear radiance
// times an exposure, then sRGB. The GLSL in shaders/ mirrors these.
#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "base/math_types.h"

namespace bounce {

// sRGB transfer function of a linear value in [0, 1].
double linear_to_srgb(double linear);

// The filmic curve of the shaders (gouraud.frag): Narkowicz's fit of ACES,
// clamped to [0, 1].
double filmic_curve(double x);

// The display encoding undone (exposure aside): the linear value that the
// sRGB curve, or with `filmic` the filmic curve then sRGB, shows as
// `encoded` in [0, 1]. At the top (a clipped pixel) it is the least value
// that shows so. The window's automatic exposure reads its picture back
// this way.
double display_to_linear(double encoded, bool filmic);

// Radiance -> 8-bit sRGB: multiply by exposure, clamp to [0, 1], encode.
glm::u8vec3 to_srgb8(const rgb& radiance, double exposure);

// An exposure that maps the 95th percentile of the luminance of the given
// radiances to 0.8 (emitters excluded by the caller); 1 when all are black.
double auto_exposure(std::span<const rgb> radiance);

// Rec. 709 luminance.
inline double luminance(const rgb& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

}  // namespace bounce
