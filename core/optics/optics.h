// Specular optics for the Whitted tracer: mirror reflection, Snell
// refraction and Fresnel reflectance. Directions are unit vectors.
#pragma once

#include <optional>

#include "scene/scene.h"

namespace bounce {

// Mirror direction of `d` about the normal `n` (either side).
vec3 reflect(const vec3& d, const vec3& n);

// Snell's law: `d` arrives at a surface with normal `n` facing against it
// (dot(d, n) < 0), going from index n1 into index n2. nullopt on total
// internal reflection.
std::optional<vec3> refract(const vec3& d, const vec3& n, double n1, double n2);

// Unpolarised Fresnel reflectance of a dielectric interface for the cosine
// of the incident angle (1 at and beyond total internal reflection).
double fresnel_dielectric(double cos_incident, double n1, double n2);

}  // namespace bounce
