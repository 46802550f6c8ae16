// The preview: the scene's surfaces as they come, before the mesher.
#include "mesh/preview_mesh.h"

#include <gtest/gtest.h>

#include "mesh_builders.h"
#include "scene/tessellate.h"

namespace bounce {
namespace {

using test_support::add_material;
using test_support::add_polygon;

TEST(PreviewMesh, HoldsEverySurfaceAsTessellatedWithItsMaterial) {
  scene s;
  const int grey = add_material(s, rgb(0.5)), lamp = add_material(s, rgb(0.2), rgb(3.0));
  add_polygon(s, {{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}}, grey);
  add_polygon(s, {{-0.5, 3, -0.5}, {0.5, 3, -0.5}, {0.5, 3, 0.5}, {-0.5, 3, 0.5}}, lamp);
  surface ball;
  ball.name = "ball";
  ball.geometry = sphere{vec3(0, 1, 0), 0.5, grey};
  s.surfaces.push_back(ball);
  const patch_mesh preview = make_preview_mesh(s);
  std::size_t expected = 0;
  for (const surface& surf : s.surfaces) expected += tessellate(surf, preview.max_edge).triangles.size();
  ASSERT_EQ(preview.element_count(), expected);
  ASSERT_EQ(preview.patch_count(), expected);
  double area[3] = {0, 0, 0};
  for (std::size_t e = 0; e < preview.element_count(); ++e)
    area[preview.element_surfaces[e]] += preview.element_areas[e];
  EXPECT_NEAR(area[0], 16.0, 1e-9);
  EXPECT_NEAR(area[1], 1.0, 1e-9);
  EXPECT_NEAR(area[2], 4.0 * 3.14159265358979 * 0.25, 0.03 * 3.14159265358979);  // facets: a little under
  for (std::size_t v = 0; v < preview.vertex_count(); ++v) {
    const int surface = preview.vertex_surfaces[v];
    EXPECT_EQ(preview.vertex_rho[v], surface == 1 ? rgb(0.2) : rgb(0.5)) << v;
    EXPECT_EQ(preview.vertex_emission[v].r > 0.0, surface == 1) << v;
  }
  for (std::size_t e = 0; e < preview.element_count(); ++e) {
    if (preview.element_surfaces[e] == 0) {
      EXPECT_NEAR(preview.element_normals[e].y, 1.0, 1e-12);
    }
  }
}

}  // namespace
}  // namespace bounce
