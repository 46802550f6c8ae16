// Shadow outlines (shadow_outlines.h) against the closed form of a square
// panel's shadow under a square light: the umbra and penumbra of two
// parallel squares are squares whose corners follow from similar triangles.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh/shadow_outlines.h"

namespace bounce {
namespace {

// A horizontal square of half-size `half` at height y, centred at (x, z),
// as two triangles facing up (or down).
void add_square(triangle_mesh& m, double x, double y, double z, double half, int material, bool facing_up) {
  const int base = int(m.positions.size());
  for (const vec3& p : {vec3(x - half, y, z - half), vec3(x - half, y, z + half), vec3(x + half, y, z + half),
                        vec3(x + half, y, z - half)}) {
    m.positions.push_back(p);
    m.normals.push_back(vec3(0, facing_up ? 1 : -1, 0));
    m.uvs.push_back(vec2(0.0));
  }
  if (facing_up) {
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
  } else {
    m.triangles.push_back({base, base + 2, base + 1});
    m.triangles.push_back({base, base + 3, base + 2});
  }
  m.materials.push_back(material);
  m.materials.push_back(material);
}

struct panel_scene {
  std::vector<triangle_mesh> surfaces{3};
  std::vector<bool> flat{true, true, true};
  std::vector<material> materials{2};
  // Floor of half-size 2 at y = 0; a panel of half-size b at height h; a
  // light of half-size a at height H, facing down.
  double a = 0.1, b = 0.3, h = 1.0, H = 2.0;

  panel_scene() {
    materials[0].rho = rgb(0.5);
    materials[1].ke = rgb(10.0);
    add_square(surfaces[0], 0, 0, 0, 2.0, 0, true);
    add_square(surfaces[1], 0, h, 0, b, 0, true);
    add_square(surfaces[2], 0, H, 0, a, 1, false);
  }
  double penumbra_half() const { return (b * H + a * h) / (H - h); }
  double umbra_half() const { return (b * H - a * h) / (H - h); }
};

double square_distance(const vec3& p) {
  return std::max(std::abs(p.x), std::abs(p.z));  // the floor's squares are centred at the origin
}

TEST(ShadowOutlines, CutTheFloorAlongTheUmbraAndPenumbraOfAPanel) {
  panel_scene s;
  const shadow_outline_stats stats = cut_shadow_outlines(s.surfaces, s.flat, s.materials, {}, 5.0, 1.0);
  EXPECT_EQ(stats.lights, 1u);
  EXPECT_GE(stats.shadows, 1u);
  EXPECT_EQ(stats.triangles_left, 0u);
  const triangle_mesh& floor = s.surfaces[0];
  const double P = s.penumbra_half(), U = s.umbra_half();  // 0.7 and 0.5
  // The outlines' corners are vertices of the floor.
  for (double half : {P, U})
    for (double sx : {-1.0, 1.0})
      for (double sz : {-1.0, 1.0}) {
        const vec3 corner(sx * half, 0.0, sz * half);
        const bool found = std::any_of(floor.positions.begin(), floor.positions.end(),
                                       [&](const vec3& p) { return glm::length(p - corner) < 1e-6; });
        EXPECT_TRUE(found) << "no vertex at (" << corner.x << ", " << corner.z << ")";
      }
  // Every triangle lies in one region: umbra, penumbra or lit, and they
  // tile the floor.
  constexpr double eps = 1e-6;
  double area = 0.0;
  std::size_t in_umbra = 0, in_penumbra = 0;
  for (const glm::ivec3& t : floor.triangles) {
    const vec3 a = floor.positions[t[0]], b = floor.positions[t[1]], c = floor.positions[t[2]];
    const double cross_y = glm::cross(b - a, c - a).y;
    EXPECT_GT(cross_y, 0.0);  // still facing up
    area += 0.5 * cross_y;
    const double centre = square_distance((a + b + c) / 3.0);
    double lo = INFINITY, hi = 0.0;
    for (const vec3& p : {a, b, c}) {
      lo = std::min(lo, square_distance(p));
      hi = std::max(hi, square_distance(p));
    }
    if (centre < U) {
      ++in_umbra;
      EXPECT_LE(hi, U + eps);
    } else if (centre < P) {
      ++in_penumbra;
      EXPECT_GE(lo, U - eps);
      EXPECT_LE(hi, P + eps);
    } else {
      EXPECT_GE(lo, P - eps);
    }
  }
  EXPECT_NEAR(area, 16.0, 1e-9);
  EXPECT_GT(in_umbra, 0u);
  EXPECT_GT(in_penumbra, 0u);
  // No vertex inside another triangle's edge: the regions meet corner to
  // corner (a T-vertex would tear the Gouraud picture).
  for (const glm::ivec3& t : floor.triangles)
    for (int k = 0; k < 3; ++k) {
      const vec3 p = floor.positions[t[k]], q = floor.positions[t[(k + 1) % 3]];
      for (std::size_t v = 0; v < floor.positions.size(); ++v) {
        const vec3 x = floor.positions[v];
        if (glm::length(x - p) < 1e-9 || glm::length(x - q) < 1e-9) continue;
        const double along = glm::dot(x - p, q - p) / glm::dot(q - p, q - p);
        if (along <= 0.0 || along >= 1.0) continue;
        const bool used = std::any_of(floor.triangles.begin(), floor.triangles.end(), [&](const glm::ivec3& u) {
          return u[0] == int(v) || u[1] == int(v) || u[2] == int(v);
        });
        if (used) {
          EXPECT_GT(glm::length(p + along * (q - p) - x), 1e-7) << "T-vertex " << v;
        }
      }
    }
  // The panel and the light are not cut.
  EXPECT_EQ(s.surfaces[1].triangles.size(), 2u);
  EXPECT_EQ(s.surfaces[2].triangles.size(), 2u);
}

TEST(ShadowOutlines, LeaveSmoothShadowsToTheSolver) {
  // The penumbra (0.28 wide) is wider than an element of 0.2: not outlined.
  panel_scene s;
  const shadow_outline_stats stats = cut_shadow_outlines(s.surfaces, s.flat, s.materials, {}, 5.0, 0.2);
  EXPECT_EQ(stats.shadows, 0u);
  EXPECT_EQ(s.surfaces[0].triangles.size(), 2u);
}

TEST(ShadowOutlines, OutlineNothingWhenNoFewLightsCarryThePower) {
  // Twelve equal lamps: eight carry two thirds of the power, not 80%.
  panel_scene s;
  s.surfaces[2] = {};
  for (int i = 0; i < 12; ++i) add_square(s.surfaces[2], -1.5 + 0.25 * i, s.H, 0, 0.05, 1, false);
  EXPECT_EQ(cut_shadow_outlines(s.surfaces, s.flat, s.materials, {}, 5.0, 1.0).lights, 0u);
  EXPECT_EQ(s.surfaces[0].triangles.size(), 2u);
  // A point light carrying the power: its shadow edge is a jump in
  // radiance, which an outline alone would smear; not outlined either.
  panel_scene p;
  p.surfaces[2] = {};
  const shadow_outline_stats stats =
      cut_shadow_outlines(p.surfaces, p.flat, p.materials, {{vec3(0, 2, 0), rgb(10.0)}}, 5.0, 1.0);
  EXPECT_EQ(stats.shadows, 0u);
}

TEST(ShadowOutlines, TakeOnlyConvexOccluders) {
  // An L-shaped panel's hull would cast a shadow it does not have.
  panel_scene s;
  s.surfaces[1] = {};
  add_square(s.surfaces[1], 0.0, s.h, 0.0, 0.15, 0, true);
  add_square(s.surfaces[1], 0.3, s.h, 0.0, 0.15, 0, true);
  add_square(s.surfaces[1], 0.0, s.h, 0.3, 0.15, 0, true);
  EXPECT_EQ(cut_shadow_outlines(s.surfaces, s.flat, s.materials, {}, 5.0, 1.0).shadows, 0u);
  // The same squares as one convex panel (a 2 x 2 grid) are outlined.
  add_square(s.surfaces[1], 0.3, s.h, 0.3, 0.15, 0, true);
  EXPECT_GE(cut_shadow_outlines(s.surfaces, s.flat, s.materials, {}, 5.0, 1.0).shadows, 1u);
}

TEST(ShadowOutlines, ReachTheElementsThroughTheMesher) {
  // The same panel through make_patch_mesh: the outline's corners are
  // element corners, and the mesh says how many shadows it outlined.
  scene s;
  s.materials.resize(2);
  s.materials[0].rho = rgb(0.5);
  s.materials[1].ke = rgb(10.0);
  auto square = [&](double y, double half, int material, bool up) {
    polygon_mesh m;
    m.positions = {vec3(-half, y, -half), vec3(-half, y, half), vec3(half, y, half), vec3(half, y, -half)};
    polygon_face f;
    f.position = up ? std::vector<int>{0, 1, 2, 3} : std::vector<int>{0, 3, 2, 1};
    f.material = material;
    m.faces.push_back(f);
    surface surf;
    surf.geometry = std::move(m);
    s.surfaces.push_back(std::move(surf));
  };
  square(0.0, 2.0, 0, true);
  square(1.0, 0.3, 0, true);
  square(2.0, 0.1, 1, false);
  mesher_params params;
  params.max_edge = 1.0;
  params.shadow_outlines = true;
  patch_mesh mesh;
  std::string error;
  ASSERT_TRUE(make_patch_mesh(s, params, mesh, error)) << error;
  EXPECT_EQ(mesh.shadow_lights, 1u);
  EXPECT_GE(mesh.shadow_outlines, 1u);
  EXPECT_GT(mesh.shadow_triangles_split, 0u);
  const vec3 umbra_corner(0.5, 0.0, 0.5);
  const bool found = std::any_of(mesh.positions.begin(), mesh.positions.end(),
                                 [&](const vec3& p) { return glm::length(p - umbra_corner) < 1e-6; });
  EXPECT_TRUE(found);
  params.shadow_outlines = false;
  patch_mesh plain;
  ASSERT_TRUE(make_patch_mesh(s, params, plain, error)) << error;
  EXPECT_EQ(plain.shadow_outlines, 0u);
}

}  // namespace
}  // namespace bounce
