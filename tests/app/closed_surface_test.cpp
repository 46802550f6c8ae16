// Which specular surfaces the live view may draw with back faces culled
// (closed_surface.h): closed, consistently wound, outward; nothing else.
#include <gtest/gtest.h>

#include "mesh_builders.h"
#include "render/closed_surface.h"
#include "render/mesh_arrays.h"

namespace bounce {
namespace {

using gl::bounds_solid_outward;

const std::vector<glm::vec3> corners = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
// Counter-clockwise seen from outside.
const std::vector<unsigned int> tetrahedron = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

TEST(ClosedSurface, AnOutwardTetrahedronIsASolid) {
  EXPECT_TRUE(bounds_solid_outward(tetrahedron, 0, tetrahedron.size(), corners));
  // The same far from the origin (the volume is taken about a corner).
  std::vector<glm::vec3> far = corners;
  for (glm::vec3& p : far) p += glm::vec3(1e5f, -2e5f, 3e5f);
  EXPECT_TRUE(bounds_solid_outward(tetrahedron, 0, tetrahedron.size(), far));
  // A range within a longer index list.
  std::vector<unsigned int> longer = {0, 1, 2};
  longer.insert(longer.end(), tetrahedron.begin(), tetrahedron.end());
  EXPECT_TRUE(bounds_solid_outward(longer, 3, tetrahedron.size(), corners));
}

TEST(ClosedSurface, InwardOpenOrInconsistentSurfacesAreNot) {
  std::vector<unsigned int> inward = tetrahedron;
  for (std::size_t t = 0; t < inward.size(); t += 3) std::swap(inward[t + 1], inward[t + 2]);
  EXPECT_FALSE(bounds_solid_outward(inward, 0, inward.size(), corners)) << "a room: seen from inside";

  const std::vector<unsigned int> open(tetrahedron.begin(), tetrahedron.begin() + 9);
  EXPECT_FALSE(bounds_solid_outward(open, 0, open.size(), corners)) << "one face missing";

  std::vector<unsigned int> flipped = tetrahedron;
  std::swap(flipped[1], flipped[2]);  // one face wound the other way
  EXPECT_FALSE(bounds_solid_outward(flipped, 0, flipped.size(), corners));

  std::vector<unsigned int> doubled = tetrahedron;
  doubled.insert(doubled.end(), tetrahedron.begin(), tetrahedron.end());
  EXPECT_FALSE(bounds_solid_outward(doubled, 0, doubled.size(), corners)) << "coincident faces";

  EXPECT_FALSE(bounds_solid_outward(tetrahedron, 0, tetrahedron.size(), {})) << "no positions";
  EXPECT_FALSE(bounds_solid_outward(tetrahedron, 3, tetrahedron.size(), corners)) << "range past the end";
  const std::vector<unsigned int> bad_index = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 9};
  EXPECT_FALSE(bounds_solid_outward(bad_index, 0, bad_index.size(), corners));
}

TEST(ClosedSurface, TheViewCullsAMirrorSphereButNotAPlanarMirror) {
  scene s;
  const int m = test_support::add_material(s, rgb(0.1));
  s.materials[std::size_t(m)].kr = rgb(0.8);
  surface ball;
  ball.name = "ball";
  ball.geometry = sphere{vec3(0.0, 1.0, 0.0), 0.5, m};
  s.surfaces.push_back(ball);
  test_support::add_polygon(s, {{-2, 0, -1}, {2, 0, -1}, {2, 2, -1}, {-2, 2, -1}}, m, "wall mirror");
  const auto source = std::make_shared<const scene>(s);
  const gl::mesh_arrays arrays = gl::make_mesh_arrays(test_support::mesh_of(s, 0.3), source);
  ASSERT_EQ(arrays.probes.size(), 2u);
  for (const gl::specular_surface& probe : arrays.probes) {
    const std::string& name = s.surfaces[std::size_t(probe.surface)].name;
    EXPECT_EQ(probe.solid, name == "ball") << name;
  }
}

}  // namespace
}  // namespace bounce
