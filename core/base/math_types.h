// The numeric types every folder shares: positions and directions in
// double precision (scene units), colours as one double per RGB channel,
// and the reductions of a colour to one number.
#pragma once

#include <algorithm>

#include <glm/glm.hpp>

namespace bounce {

using vec2 = glm::dvec2;
using vec3 = glm::dvec3;
using rgb = glm::dvec3;

// Sum over channels: the scalar that picks shooters and measures power.
inline double channel_sum(const rgb& c) {
  return c.r + c.g + c.b;
}

inline double channel_mean(const rgb& c) {
  return (c.r + c.g + c.b) / 3.0;
}

inline double channel_max(const rgb& c) {
  return std::max(c.r, std::max(c.g, c.b));
}

// Whether any channel is above zero.
inline bool any_positive(const rgb& c) {
  return c.r > 0.0 || c.g > 0.0 || c.b > 0.0;
}

}  // namespace bounce
