// Camera matrices (GL conventions: right-handed view space looking down -z,
// clip depth in [-1, 1]). GL-free: the renderer and the ray tracer share it.
#pragma once

#include <glm/mat4x4.hpp>

#include "scene/scene.h"
#include "scene/scene_io.h"

namespace bounce {

glm::dmat4 view_matrix(const camera& c);

// Perspective projection for the camera's vertical field of view and its
// image aspect; near and far planes enclose `bounds` as seen from the eye.
glm::dmat4 projection_matrix(const camera& c, const bounds3& bounds);

// Unit direction of the ray through image point (x, y) in pixels, (0, 0) the
// top-left corner of the image, for ray tracing with the same camera.
vec3 camera_ray_direction(const camera& c, double x, double y);

}  // namespace bounce
