// Directions from two uniform numbers in [0, 1): around a normal with a
// cosine density, or uniform on the sphere. The tracers, the photon pass,
// the irradiance cache and the ray benchmark all draw their directions
// here, so that a sample means the same direction everywhere.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/math_types.h"

namespace bounce {

// A right-handed orthonormal basis (t, b, n) around the unit vector n,
// continuous everywhere but at n.z = -0 (Duff et al. 2017).
inline void orthonormal_basis(const vec3& n, vec3& t, vec3& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = vec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = vec3(c, sign + n.y * n.y * a, -n.y);
}

// Cosine-distributed about the unit normal n (Malley: uniform on the
// disc, lifted to the hemisphere).
inline vec3 cosine_direction(const vec3& n, double u1, double u2) {
  vec3 t, b;
  orthonormal_basis(n, t, b);
  const double r = std::sqrt(u1), phi = 2.0 * std::numbers::pi * u2;
  return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0, 1.0 - u1)) * n);
}

// Uniform on the unit sphere.
inline vec3 sphere_direction(double u1, double u2) {
  const double z = 1.0 - 2.0 * u1, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * std::numbers::pi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Uniform in the cone of directions within angle acos(cos_max) of the unit
// axis (solid angle 2 pi (1 - cos_max)).
inline vec3 cone_direction(const vec3& axis, double cos_max, double u1, double u2) {
  vec3 t, b;
  orthonormal_basis(axis, t, b);
  const double z = 1.0 - u1 * (1.0 - cos_max), r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * std::numbers::pi * u2;
  return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b + z * axis);
}

}  // namespace bounce
