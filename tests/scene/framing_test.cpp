// Framing: the bounding box of a scene and the camera fitted to it when
// the scene brings none (here a bare OBJ, as `bounce model.obj` opens it).
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "mesh_builders.h"
#include "scene/framing.h"
#include "scene/scene_io.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::load_ok;

using test_support::source_path;

TEST(Framing, BareObjGetsACameraLookingIntoTheOpenSide) {
  scene s = load_ok(source_path("assets/cornell_box/cornell_box.obj"));
  // The box is open towards -z: the fitted camera stands there, looking +z.
  EXPECT_LT(s.view.eye.z, 0.0);
  EXPECT_NEAR(s.view.eye.x, s.view.target.x, 1e-9);
  EXPECT_GT(s.view.target.z, s.view.eye.z);
  // And it sees the whole bounding sphere.
  bounds3 b = scene_bounds(s);
  double radius = 0.5 * glm::length(b.max - b.min);
  double distance = glm::length(s.view.target - s.view.eye);
  EXPECT_GE(std::asin(radius / distance), 0.0);
  EXPECT_LE(std::asin(radius / distance), glm::radians(s.view.fov_y_degrees) * 0.5 + 1e-9);
}

}  // namespace
}  // namespace bounce
