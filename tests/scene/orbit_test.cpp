// Camera navigation maths.
#include <cmath>

#include <gtest/gtest.h>

#include "scene/camera_math.h"
#include "scene/framing.h"
#include "scene/orbit.h"

namespace bounce {
namespace {

camera scene_camera() {
  camera c;
  c.eye = vec3(278, 273, -800);
  c.target = vec3(278, 273, 0);
  c.fov_y_degrees = 39.3;
  return c;
}

TEST(Orbit, RoundTripsTheSceneCamera) {
  const camera c = scene_camera();
  const camera back = camera_from_orbit(orbit_from_camera(c), c);
  EXPECT_NEAR(glm::length(back.eye - c.eye), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(back.target - c.target), 0.0, 1e-12);
  camera tilted = c;
  tilted.eye = vec3(100, 500, -300);
  const camera t = camera_from_orbit(orbit_from_camera(tilted), tilted);
  EXPECT_NEAR(glm::length(t.eye - tilted.eye), 0.0, 1e-9);
}

TEST(Orbit, RotatingKeepsDistanceAndTargetAndNeverFlips) {
  orbit_state o = orbit_from_camera(scene_camera());
  const double d = o.distance;
  orbit_rotate(o, 120, 40);
  const camera c = camera_from_orbit(o, scene_camera());
  EXPECT_NEAR(glm::length(c.eye - c.target), d, 1e-9);
  EXPECT_EQ(c.target, vec3(278, 273, 0));
  orbit_rotate(o, 0, 100000);  // far past the pole
  EXPECT_LT(o.pitch, glm::radians(89.0) + 1e-12);
  // 300 pixels right = 90 degrees about +y.
  orbit_state q = orbit_from_camera(scene_camera());
  orbit_rotate(q, 300, 0);
  const camera r = camera_from_orbit(q, scene_camera());
  EXPECT_NEAR(r.eye.z, 0.0, 1e-9);
}

TEST(Orbit, PanFollowsTheCursorAndZoomScales) {
  orbit_state o = orbit_from_camera(scene_camera());
  // Dragging a full viewport height moves the target by the visible height.
  orbit_pan(o, 0, 500, 500, 39.3);
  EXPECT_NEAR(o.target.y - 273, 2 * 800 * std::tan(glm::radians(39.3 / 2)), 1e-9);
  orbit_zoom(o, 1);
  EXPECT_NEAR(o.distance, 720, 1e-9);
  orbit_zoom(o, -1);
  EXPECT_NEAR(o.distance, 800, 1e-9);
}

TEST(Orbit, FlyAndFrame) {
  orbit_state o = orbit_from_camera(scene_camera());
  orbit_fly(o, 100, 0, 0);  // forward is +z for this camera
  EXPECT_NEAR(o.target.z, 100, 1e-9);
  orbit_frame(o, bounds3{vec3(0.0), vec3(2.0)}, 60.0);
  EXPECT_EQ(o.target, vec3(1.0));
  EXPECT_NEAR(o.distance, std::sqrt(3.0) / std::sin(glm::radians(30.0)), 1e-12);
}

// Orbiting about the point under the cursor: the point stays at its pixel
// while the view turns as a plain orbit turns it.
TEST(Orbit, TurningAboutAPointKeepsItOnItsPixel) {
  camera base = scene_camera();
  base.width = 640;
  base.height = 480;
  const vec3 pivot(450, 120, 400);  // off the centre of the view
  auto pixel_of = [&](const orbit_state& o) {
    const camera c = camera_from_orbit(o, base);
    const glm::dvec4 clip = projection_matrix(c, {vec3(0), vec3(600)}) * view_matrix(c) * glm::dvec4(pivot, 1.0);
    return glm::dvec2(clip.x / clip.w, clip.y / clip.w);
  };
  orbit_state o = orbit_from_camera(base);
  const glm::dvec2 before = pixel_of(o);
  orbit_state plain = o;
  orbit_rotate(plain, 150, -60);
  orbit_rotate_about(o, pivot, 150, -60);
  EXPECT_NEAR(o.yaw, plain.yaw, 1e-12);
  EXPECT_NEAR(o.pitch, plain.pitch, 1e-12);
  EXPECT_NEAR(o.distance, plain.distance, 1e-9);
  const glm::dvec2 after = pixel_of(o);
  EXPECT_NEAR(after.x, before.x, 1e-9);
  EXPECT_NEAR(after.y, before.y, 1e-9);
  // About the target itself it is the plain orbit.
  orbit_state t = orbit_from_camera(base);
  orbit_rotate_about(t, t.target, 150, -60);
  EXPECT_NEAR(glm::length(t.target - plain.target), 0.0, 1e-9);
}

// The axis views look along the scene camera's axis, its opposite, from the
// sides, and from above and below, about the same target.
TEST(Orbit, AxisViewsSquareToTheSceneCamera) {
  camera c = scene_camera();
  c.eye = vec3(300, 273, -800);  // a little off the axis: still the front
  const double front = front_yaw_of(c);
  orbit_state o = orbit_from_camera(c);
  orbit_axis_view(o, axis_view::front, front);
  camera v = camera_from_orbit(o, c);
  EXPECT_NEAR(glm::normalize(v.target - v.eye).z, 1.0, 1e-12);
  orbit_axis_view(o, axis_view::back, front);
  v = camera_from_orbit(o, c);
  EXPECT_NEAR(glm::normalize(v.target - v.eye).z, -1.0, 1e-12);
  orbit_axis_view(o, axis_view::right, front);
  v = camera_from_orbit(o, c);
  EXPECT_NEAR(std::abs(glm::normalize(v.target - v.eye).x), 1.0, 1e-12);
  orbit_axis_view(o, axis_view::top, front);
  v = camera_from_orbit(o, c);
  EXPECT_LT(glm::normalize(v.target - v.eye).y, -0.99);
  EXPECT_EQ(v.target, c.target);
}

}  // namespace
}  // namespace bounce
