// The window's camera in a room: an orbit begun inside a room never takes
// the eye through a wall, and one begun outside is free.
#include <gtest/gtest.h>

#include "scene/orbit.h"
#include "scene/procedural.h"
#include "trace/ray_scene.h"
#include "viewer/input.h"

namespace bounce {
namespace {

bool inside_room(const vec3& p) {  // make_box_room: 10 x 3 x 10 m about the origin
  return std::abs(p.x) < 5.0 && std::abs(p.z) < 5.0 && p.y > 0.0 && p.y < 3.0;
}

TEST(Navigation, TheEyeStaysInFrontOfTheWallsOfARoom) {
  const scene room = make_box_room(1);
  const ray_scene rays(room);
  orbit_state o;
  o.target = vec3(0, 1.5, 0);
  o.distance = 3.0;
  camera base;
  for (int step = 0; step < 24; ++step) {
    orbit_rotate(o, 100, 7);  // 30 degrees a step, round and up
    o.distance = 12.0;        // as if zoomed out past the wall
    keep_eye_in_front_of_walls(o, rays);
    const camera c = camera_from_orbit(o, base);
    EXPECT_TRUE(inside_room(c.eye)) << "step " << step << ": eye at " << c.eye.x << ", " << c.eye.y << ", " << c.eye.z;
    EXPECT_GT(o.distance, 0.5);  // in front of the wall, not pressed onto the target
  }
  // With nothing between the target and the eye, the orbit is left alone.
  o.distance = 1.0;
  keep_eye_in_front_of_walls(o, rays);
  EXPECT_DOUBLE_EQ(o.distance, 1.0);
}

}  // namespace
}  // namespace bounce
