#include "scene/sky.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "base/random_stream.h"

namespace bounce {

rgb sky_radiance(const sky_light& sky, const vec3& dir) {
  const double up = std::max(0.0, glm::dot(dir, glm::normalize(sky.up)));
  return sky.horizon + (sky.zenith - sky.horizon) * up;
}

rgb escaped_radiance(const scene& s, const vec3& dir) {
  return s.sky.on() ? sky_radiance(s.sky, dir) : s.background;
}

rgb open_sky_irradiance(const sky_light& sky) {
  return std::numbers::pi * sky.horizon + (2.0 * std::numbers::pi / 3.0) * (sky.zenith - sky.horizon);
}

vec3 stratified_cosine_direction(const vec3& n, int k, int count, std::uint64_t seed) {
  const int side = std::max(1, int(std::sqrt(double(count))));
  // One jittered sample in each of side x side strata of the unit square.
  auto unit = [](std::uint64_t x) { return unit_interval(murmur_mix64(x)); };
  const std::uint64_t key = seed * golden_gamma + std::uint64_t(k);
  const double u = ((k % side) + unit(key)) / side;
  const double v = (((k / side) % side) + unit(key ^ 0x632be59bd9b4e019ull)) / side;
  // Malley: uniform on the disc, lifted to the hemisphere.
  const double r = std::sqrt(u), phi = 2.0 * std::numbers::pi * v;
  const double x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0, 1.0 - u));
  const vec3 a = std::abs(n.x) > 0.9 ? vec3(0, 1, 0) : vec3(1, 0, 0);
  const vec3 t = glm::normalize(glm::cross(a, n)), b = glm::cross(n, t);
  return glm::normalize(x * t + y * b + z * n);
}

}  // namespace bounce
