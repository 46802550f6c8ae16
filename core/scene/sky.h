// The sky (scene.h's sky_light): its radiance in a direction, what rays
// that leave the scene see, and the directions its light is sampled along.
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace bounce {

// Radiance arriving from direction `dir` (unit, pointing away from the
// scene, towards the sky).
rgb sky_radiance(const sky_light& sky, const vec3& dir);

// What a ray leaving the scene along `dir` sees: the sky where there is
// one, else the background colour.
rgb escaped_radiance(const scene& s, const vec3& dir);

// Irradiance of the unoccluded sky on a plane facing `up`: pi * horizon +
// 2 pi / 3 * (zenith - horizon). The closed form the tests check against.
rgb open_sky_irradiance(const sky_light& sky);

// Direction `k` of `count` (a square number is best) over the hemisphere
// around `n`, cosine-weighted and stratified, jittered within its stratum
// by `seed` so that neighbouring points do not share their directions: the
// mean of L(dir) over them, times pi, estimates the irradiance.
vec3 stratified_cosine_direction(const vec3& n, int k, int count, std::uint64_t seed);

}  // namespace bounce
