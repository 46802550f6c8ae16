// Camera matrices (GL conventions: right-handed view space looking down -z,
// clip depth in [-1, 1]). GL-free: the renderer and the ray tracer share it.
#pragma once

#include <glm/mat4x4.hpp>

#include "scene/framing.h"
#include "scene/scene.h"

namespace bounce {

glm::dmat4 view_matrix(const camera& c);

// Perspective projection for the camera's vertical field of view and its
// image aspect; near and far planes enclose `bounds` as seen from the eye.
glm::dmat4 projection_matrix(const camera& c, const bounds3& bounds);

// The camera's image plane at distance 1 from the eye, worked out once for
// the many rays of a picture: the direction through image point (x, y) in
// pixels, (0, 0) the top-left corner, is normalize(corner + x dx + y dy).
struct camera_rays {
  vec3 corner{0.0}, dx{0.0}, dy{0.0};
  explicit camera_rays(const camera& c);
  vec3 direction(double x, double y) const { return glm::normalize(corner + x * dx + y * dy); }
};

// Unit direction of the ray through image point (x, y) in pixels, (0, 0) the
// top-left corner of the image, for ray tracing with the same camera (one
// ray; camera_rays for a picture's worth).
vec3 camera_ray_direction(const camera& c, double x, double y);

}  // namespace bounce
