#include "scene/camera_math.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace bounce {

glm::dmat4 view_matrix(const camera& c) {
  return glm::lookAt(c.eye, c.target, c.up);
}

glm::dmat4 projection_matrix(const camera& c, const bounds3& bounds) {
  // Far: the farthest box corner. Near: the box's smallest depth along the
  // view axis (a linear function: its minimum is at a corner), a little
  // closer, so that an eye outside the scene spends the depth buffer's
  // precision on the scene only: 24 bits then resolve about 1e-4 mm at the
  // back of the Cornell box, where near = far / 1e4 resolved only 0.4 mm
  // and a light 0.1 mm under the ceiling z-fought. Clamped to 1e-4 of far
  // when the box reaches the eye's plane (eye inside the scene).
  const vec3 forward = glm::normalize(c.target - c.eye);
  double farthest = 0.0, nearest = INFINITY;
  for (int i = 0; i < 8; ++i) {
    const vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                      (i & 4) ? bounds.max.z : bounds.min.z);
    farthest = std::max(farthest, glm::length(corner - c.eye));
    nearest = std::min(nearest, glm::dot(corner - c.eye, forward));
  }
  const double far_plane = std::max(farthest * 1.01, 1e-6);
  const double near_plane = std::max(nearest * 0.99, far_plane * 1e-4);
  return glm::perspective(glm::radians(c.fov_y_degrees), double(c.width) / double(c.height), near_plane, far_plane);
}

camera_rays::camera_rays(const camera& c) {
  const vec3 forward = glm::normalize(c.target - c.eye);
  const vec3 right = glm::normalize(glm::cross(forward, c.up));
  const vec3 up = glm::cross(right, forward);
  const double half_height = std::tan(glm::radians(c.fov_y_degrees) * 0.5);
  const double half_width = half_height * double(c.width) / double(c.height);
  // u = (2 x / width - 1) half_width along right, v = (1 - 2 y / height) half_height along up.
  corner = forward - right * half_width + up * half_height;
  dx = right * (2.0 * half_width / c.width);
  dy = -up * (2.0 * half_height / c.height);
}

vec3 camera_ray_direction(const camera& c, double x, double y) {
  return camera_rays(c).direction(x, y);
}

}  // namespace bounce
