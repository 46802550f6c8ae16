#include "scene/orbit.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

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

void orbit_rotate_about(orbit_state& o, const vec3& pivot, double dx, double dy) {
  orbit_state turned = o;
  orbit_rotate(turned, dx, dy);
  // The rotation that takes the old view direction to the new one: the
  // pitch about the camera's right axis, then the yaw about +y.
  // (A turn by a about right = y x back lowers the pitch by a; the pitch
  // stays under 89 degrees, so `right` is defined.)
  const vec3 right = glm::normalize(glm::cross(vec3(0, 1, 0), backwards(o)));
  const glm::dquat turn =
      glm::angleAxis(turned.yaw - o.yaw, vec3(0, 1, 0)) * glm::angleAxis(o.pitch - turned.pitch, right);
  turned.target = pivot + turn * (o.target - pivot);
  o = turned;
}

void orbit_axis_view(orbit_state& o, axis_view view, double front_yaw) {
  const double quarter = 0.5 * 3.14159265358979323846;
  switch (view) {
    case axis_view::front:
      o.yaw = front_yaw, o.pitch = 0.0;
      break;
    case axis_view::back:
      o.yaw = front_yaw + 2.0 * quarter, o.pitch = 0.0;
      break;
    case axis_view::right:
      o.yaw = front_yaw + quarter, o.pitch = 0.0;
      break;
    case axis_view::left:
      o.yaw = front_yaw - quarter, o.pitch = 0.0;
      break;
    case axis_view::top:
      o.yaw = front_yaw, o.pitch = max_pitch;
      break;
    case axis_view::bottom:
      o.yaw = front_yaw, o.pitch = -max_pitch;
      break;
  }
}

double front_yaw_of(const camera& c) {
  const double quarter = 0.5 * 3.14159265358979323846;
  return quarter * std::round(orbit_from_camera(c).yaw / quarter);
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
