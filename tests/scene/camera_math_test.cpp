// Camera matrices: projection and camera rays agree.
#include <cmath>

#include <gtest/gtest.h>

#include "scene/camera_math.h"
#include "scene/framing.h"

namespace bounce {
namespace {

camera cornell_camera() {
  camera c;
  c.eye = vec3(278, 273, -800);
  c.target = vec3(278, 273, 0);
  c.up = vec3(0, 1, 0);
  c.fov_y_degrees = 39.3;
  c.width = 512;
  c.height = 256;
  return c;
}

TEST(CameraMath, ProjectionAndRaysAgree) {
  const camera c = cornell_camera();
  const bounds3 box{vec3(0.0), vec3(556, 548.8, 559.2)};
  const glm::dmat4 clip = projection_matrix(c, box) * view_matrix(c);
  // A point along the ray through a pixel projects back onto that pixel.
  for (auto [x, y] : {std::pair{256.0, 128.0}, std::pair{10.5, 3.5}, std::pair{500.0, 250.0}}) {
    // 900 mm deep: within the box's depth range, which the near plane hugs.
    const vec3 d = camera_ray_direction(c, x, y);
    const vec3 p = c.eye + d / d.z * 900.0;
    const glm::dvec4 q = clip * glm::dvec4(p, 1.0);
    const double px = (q.x / q.w * 0.5 + 0.5) * c.width;
    const double py = (1.0 - (q.y / q.w * 0.5 + 0.5)) * c.height;  // image rows go down
    EXPECT_NEAR(px, x, 1e-9);
    EXPECT_NEAR(py, y, 1e-9);
    EXPECT_GT(q.z / q.w, -1.0);  // inside the depth range
    EXPECT_LT(q.z / q.w, 1.0);
  }
  // The centre ray looks at the target; the top edge is half the field of view up.
  EXPECT_NEAR(glm::length(camera_ray_direction(c, 256, 128) - vec3(0, 0, 1)), 0.0, 1e-12);
  const vec3 top = camera_ray_direction(c, 256, 0);
  EXPECT_NEAR(glm::degrees(std::atan2(top.y, top.z)), 39.3 / 2, 1e-9);
  // Right in the image is -x for this camera (the red wall, x = 556, is on the left).
  EXPECT_LT(camera_ray_direction(c, 511, 128).x, 0.0);
}

}  // namespace
}  // namespace bounce
