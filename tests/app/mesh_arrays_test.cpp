// The renderer's arrays: plain elements in chunks that the view culls.
#include "render/mesh_arrays.h"

#include <gtest/gtest.h>

#include "mesh_builders.h"
#include "scene/camera_math.h"
#include "scene/framing.h"

namespace bounce {
namespace {

using test_support::add_material;
using test_support::add_polygon;
using test_support::mesh_of;

// Two floors 16 m apart, a camera looking down on the left one: the right
// one's chunks are not drawn.
TEST(MeshArrays, ChunksOutsideTheViewAreNotDrawn) {
  scene s;
  const int grey = add_material(s, rgb(0.5));
  add_polygon(s, {{-10, 0, -1}, {-10, 0, 1}, {-8, 0, 1}, {-8, 0, -1}}, grey);
  add_polygon(s, {{8, 0, -1}, {8, 0, 1}, {10, 0, 1}, {10, 0, -1}}, grey);
  const patch_mesh mesh = mesh_of(s, 0.03);
  const gl::mesh_arrays arrays = gl::make_mesh_arrays(mesh, nullptr);
  ASSERT_GT(arrays.plain_chunks.size(), 8u);
  camera c;
  c.eye = vec3(-9, 3, 0);
  c.target = vec3(-9, 0, 0.01);
  c.fov_y_degrees = 60;
  c.width = c.height = 100;
  const glm::mat4 view_projection(projection_matrix(c, scene_bounds(s)) * view_matrix(c));
  std::size_t left = 0, right = 0, all_left = 0;
  for (std::size_t i = 0; i < arrays.plain_count; i += 3)
    all_left += arrays.vertices[arrays.indices[i] * gl::mesh_arrays::floats_per_vertex] < 0.0f;
  for (const auto& [first, count] : gl::visible_ranges(arrays.plain_chunks, view_projection))
    for (std::size_t i = first; i < first + count; i += 3) {
      const float x = arrays.vertices[arrays.indices[i] * gl::mesh_arrays::floats_per_vertex];
      (x < 0.0f ? left : right) += 1;
    }
  EXPECT_EQ(left, all_left);
  // At most the chunk that straddles the two floors along the curve.
  EXPECT_LE(right, gl::chunk_triangles);
  // From far above, both.
  c.eye = vec3(0, 40, 0);
  c.target = vec3(0, 0, 0.01);
  const glm::mat4 above(projection_matrix(c, scene_bounds(s)) * view_matrix(c));
  const auto ranges = gl::visible_ranges(arrays.plain_chunks, above);
  ASSERT_EQ(ranges.size(), 1u);
  EXPECT_EQ(ranges[0].second, arrays.plain_count);
}

}  // namespace
}  // namespace bounce
