// Chains of planar mirrors for the hierarchical solver's links through
// mirrors (mirror_chains.h): the image map against reflecting point by
// point, and the window cull against sampled segments.
#include <cmath>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh_builders.h"
#include "radiosity/hierarchical/mirror_chains.h"
#include "radiosity/transfer/mirror_images.h"
#include "radiosity/transfer/occlusion.h"
#include "scene/two_sided.h"

namespace bounce {
namespace {

using test_support::add_material;
using test_support::add_polygon;
using test_support::mesh_of;

// Two mirrors at right angles over a floor: a tall one facing +x at
// x = 0, a wide one facing down at y = 3.
scene two_mirrors() {
  scene s;
  const int floor = add_material(s, rgb(0.5));
  add_polygon(s, {{0, 0, -2}, {0, 0, 2}, {4, 0, 2}, {4, 0, -2}}, floor);
  const int m1 = add_material(s, rgb(0.0)), m2 = add_material(s, rgb(0.0));
  s.materials[std::size_t(m1)].kr = rgb(0.9);
  s.materials[std::size_t(m2)].kr = rgb(0.7, 0.8, 0.9);
  add_polygon(s, {{0, 0.5, -1}, {0, 2.5, -1}, {0, 2.5, 1}, {0, 0.5, 1}}, m1);
  add_polygon(s, {{1, 3, -1}, {3, 3, -1}, {3, 3, 1}, {1, 3, 1}}, m2);
  return s;
}

TEST(MirrorChains, ImagesReflectInTheLastMirrorFirst) {
  const scene s = two_mirrors();
  const patch_mesh mesh = mesh_of(s, 0.5);
  const auto set = find_planar_mirrors(s, mesh);
  ASSERT_TRUE(set);
  ASSERT_EQ(set->mirrors.size(), 2u);
  const std::vector<mirror_chain> chains = mirror_chains(*set, 2);
  ASSERT_EQ(chains.size(), 4u);  // 0, 0-1, 1, 1-0
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  for (const mirror_chain& chain : chains) {
    rgb kr(1.0);
    for (int k = 0; k < chain.path.count; ++k) kr *= set->mirrors[std::size_t(chain.path.mirrors[k])].kr;
    EXPECT_EQ(chain.path.kr, kr);
    for (int trial = 0; trial < 20; ++trial) {
      const vec3 x(u(random), u(random), u(random)), d = glm::normalize(vec3(u(random), u(random), u(random)));
      vec3 expected = x, direction = d;
      for (int k = chain.path.count - 1; k >= 0; --k) {
        const planar_mirror& m = set->mirrors[std::size_t(chain.path.mirrors[k])];
        expected = m.reflect_point(expected);
        direction = m.reflect_direction(direction);
      }
      EXPECT_LT(glm::length(chain.image(x) - expected), 1e-12);
      EXPECT_LT(glm::length(chain.image_direction(d) - direction), 1e-12);
      EXPECT_LT(glm::length(chain.source_direction(direction) - d), 1e-12);
    }
  }
}

TEST(MirrorChains, TheTwoSidesOfAMirrorMakeNoChainTogether) {
  // A two-sided mirror panel is two mirrors in one plane, facing away from
  // each other: light leaving one never reaches the other, so at depth 2
  // there are the two single chains and no pair.
  scene s;
  add_polygon(s, {{0, 0, -2}, {0, 0, 2}, {4, 0, 2}, {4, 0, -2}}, add_material(s, rgb(0.5)));
  const int m = add_material(s, rgb(0.0));
  s.materials[std::size_t(m)].kr = rgb(0.9);
  s.materials[std::size_t(m)].two_sided = true;
  add_polygon(s, {{2, 0.5, -1}, {2, 2.5, -1}, {2, 2.5, 1}, {2, 0.5, 1}}, m);
  add_back_sides(s);  // as loading a scene does
  const patch_mesh mesh = mesh_of(s, 0.5);
  const auto set = find_planar_mirrors(s, mesh);
  ASSERT_TRUE(set);
  ASSERT_EQ(set->mirrors.size(), 2u);
  EXPECT_EQ(mirror_chains(*set, 2).size(), 2u);
  EXPECT_EQ(mirror_chains(*set, 4).size(), 2u);
  // Mirrors at right angles do pass light to each other.
  const scene corner = two_mirrors();
  const patch_mesh corner_mesh = mesh_of(corner, 0.5);
  EXPECT_EQ(mirror_chains(*find_planar_mirrors(corner, corner_mesh), 3).size(), 6u);  // 0, 1, 01, 10, 010, 101
}

TEST(MirrorChains, TheWindowCullKeepsEveryPairWhoseSegmentsCrossTheMirror) {
  // Random boxes in front of the first mirror and random image boxes
  // behind it: whenever a sampled segment between them crosses the plane
  // inside the mirror's outline, the cull must let the pair through; and
  // it must cull some pairs (a test that cannot fail otherwise).
  const scene s = two_mirrors();
  const patch_mesh mesh = mesh_of(s, 0.5);
  const auto set = find_planar_mirrors(s, mesh);
  ASSERT_TRUE(set);
  const std::vector<mirror_chain> chains = mirror_chains(*set, 1);
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int crossing = 0, culled = 0;
  for (const mirror_chain& chain : chains) {
    const planar_mirror& m = set->mirrors[std::size_t(chain.path.mirrors[0])];
    for (int trial = 0; trial < 4000; ++trial) {
      vec3 lo, hi, image_lo, image_hi;
      for (int k = 0; k < 3; ++k) {
        const double a = -4.0 + 8.0 * u(random), b = a + 2.0 * u(random) * u(random);
        lo[k] = a;
        hi[k] = b;
      }
      for (int k = 0; k < 3; ++k) {
        const double a = -4.0 + 8.0 * u(random), b = a + 2.0 * u(random) * u(random);
        image_lo[k] = a;
        image_hi[k] = b;
      }
      bool crosses = false;
      for (int k = 0; k < 200 && !crosses; ++k) {
        const vec3 p = lo + (hi - lo) * vec3(u(random), u(random), u(random));
        const vec3 q = image_lo + (image_hi - image_lo) * vec3(u(random), u(random), u(random));
        const double sp = m.side(p), sq = m.side(q);
        if (!(sp > 0.0 && sq < 0.0)) continue;
        crosses = m.outline->occluded(p, q);
      }
      const bool kept = may_cross_first_mirror(*set, chain, lo, hi, image_lo, image_hi);
      if (crosses) {
        ++crossing;
        EXPECT_TRUE(kept) << "trial " << trial;
      }
      culled += kept ? 0 : 1;
    }
  }
  EXPECT_GT(crossing, 200);
  EXPECT_GT(culled, 2000);
}

}  // namespace
}  // namespace bounce
