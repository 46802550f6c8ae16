#include "scene/orbit.h"

#include <algorithm>
#include <cmath>

namespace bounce {
namespace {

constexpr double max_pitch = 89.0 * 3.14159265358979323846 / 180.0;

// Unit vector from the target towards the eye.
vec3 backwards(const orbit_state& o) {
  return {std::sin(o.yaw) * std::cos(o.pitch), std::sin(o.pitch), std::cos(o.yaw) * std::cos(o.pitch)};
}

}  // namespace

orbit_state orbit_from_camera(const camera& c) {
  orbit_state o;
  o.target = c.target;
  const vec3 d = c.eye - c.target;
  o.distance = std::max(glm::length(d), 1e-12);
  const vec3 u = d / o.distance;
  o.pitch = std::clamp(std::asin(std::clamp(u.y, -1.0, 1.0)), -max_pitch, max_pitch);
  o.yaw = std::atan2(u.x, u.z);
  return o;
}

camera camera_from_orbit(const orbit_state& o, const camera& base) {
  camera c = base;
  c.target = o.target;
  c.eye = o.target + backwards(o) * o.distance;
  c.up = vec3(0, 1, 0);
  return c;
}

void orbit_rotate(orbit_state& o, double dx, double dy) {
  const double per_pixel = 0.3 * 3.14159265358979323846 / 180.0;
  o.yaw -= dx * per_pixel;
  o.pitch = std::clamp(o.pitch + dy * per_pixel, -max_pitch, max_pitch);
}

void orbit_pan(orbit_state& o, double dx, double dy, double height, double fov_y_degrees) {
  const vec3 back = backwards(o);
  const vec3 right = glm::normalize(glm::cross(vec3(0, 1, 0), back));
  const vec3 up = glm::cross(back, right);
  // World units per pixel at the target's distance.
  const double scale = 2.0 * o.distance * std::tan(glm::radians(fov_y_degrees) * 0.5) / std::max(height, 1.0);
  o.target += (-dx * right + dy * up) * scale;
}

void orbit_zoom(orbit_state& o, double steps) {
  o.distance = std::max(o.distance * std::pow(0.9, steps), 1e-9);
}

void orbit_fly(orbit_state& o, double forward, double right, double up) {
  const vec3 back = backwards(o);
  const vec3 r = glm::normalize(glm::cross(vec3(0, 1, 0), back));
  o.target += -back * forward + r * right + vec3(0, 1, 0) * up;
}

void orbit_frame(orbit_state& o, const bounds3& b, double fov_y_degrees) {
  o.target = 0.5 * (b.min + b.max);
  const double radius = std::max(0.5 * glm::length(b.max - b.min), 1e-12);
  o.distance = radius / std::sin(glm::radians(fov_y_degrees) * 0.5);
}

}  // namespace bounce
