// Tests of tessellate.h against exact answers: areas of spheres, cylinders
// and planes, points exactly on the surfaces, closed and consistently
// oriented meshes, and the precision properties of Bezier and B-spline bases.
#include "scene/tessellate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

namespace bounce {
namespace {

using std::numbers::pi;

vec3 triangle_cross(const triangle_mesh& m, const glm::ivec3& t) {
  return glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
}

double area(const triangle_mesh& m) {
  double sum = 0.0;
  for (const glm::ivec3& t : m.triangles) sum += 0.5 * glm::length(triangle_cross(m, t));
  return sum;
}

double longest_edge(const triangle_mesh& m) {
  double longest = 0.0;
  for (const glm::ivec3& t : m.triangles)
    for (int i = 0; i < 3; ++i)
      longest = std::max(longest, glm::distance(m.positions[t[i]], m.positions[t[(i + 1) % 3]]));
  return longest;
}

// Sizes agree, indices are in range, normals are unit, no triangle is
// degenerate and each faces the way its vertex normals point.
void expect_well_formed(const triangle_mesh& m) {
  const int n = static_cast<int>(m.positions.size());
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  ASSERT_EQ(m.materials.size(), m.triangles.size());
  for (const vec3& normal : m.normals) ASSERT_NEAR(glm::length(normal), 1.0, 1e-12);
  for (const glm::ivec3& t : m.triangles) {
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(t[i] >= 0 && t[i] < n);
    ASSERT_TRUE(t.x != t.y && t.y != t.z && t.x != t.z);
    const vec3 c = triangle_cross(m, t);
    ASSERT_GT(glm::length(c), 0.0);
    const vec3 mean_normal = m.normals[t.x] + m.normals[t.y] + m.normals[t.z];
    ASSERT_GT(glm::dot(c, mean_normal), 0.0) << "triangle against its normals";
  }
}

// Uses of each undirected edge, and whether every directed edge occurs at
// most once (consistent orientation).
struct edge_census {
  std::map<std::pair<int, int>, int> uses;
  bool oriented = true;
};

edge_census count_edges(const triangle_mesh& m) {
  edge_census census;
  std::map<std::pair<int, int>, int> directed;
  for (const glm::ivec3& t : m.triangles)
    for (int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3];
      ++census.uses[{std::min(a, b), std::max(a, b)}];
      if (++directed[{a, b}] > 1) census.oriented = false;
    }
  return census;
}

// Closed and consistently oriented: each edge in exactly two triangles.
::testing::AssertionResult is_closed(const triangle_mesh& m) {
  const edge_census census = count_edges(m);
  if (!census.oriented) return ::testing::AssertionFailure() << "a directed edge is used twice";
  for (const auto& [edge, uses] : census.uses)
    if (uses != 2)
      return ::testing::AssertionFailure()
             << "edge " << edge.first << "-" << edge.second << " used " << uses << " times";
  return ::testing::AssertionSuccess();
}

// The largest turn of the normal along any edge, in degrees.
double largest_turn_degrees(const triangle_mesh& m) {
  double widest = 0.0;
  for (const glm::ivec3& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      widest = std::max(widest, std::acos(std::clamp(glm::dot(m.normals[t[k]], m.normals[t[(k + 1) % 3]]), -1.0, 1.0)));
  return widest * 180.0 / pi;
}

// ---------------------------------------------------------------------------
// Sphere

TEST(TessellateSphere, AreaConvergesToFourPiRSquared) {
  const sphere s{vec3(1.0, -2.0, 0.5), 1.7, 3};
  const double exact = 4.0 * pi * s.radius * s.radius;
  double previous = 1.0;
  // Edges of r / 4 and finer: coarser ones meet the curvature bound below.
  for (double fraction : {0.25, 0.125, 0.0625}) {
    const triangle_mesh m = tessellate(s, fraction * s.radius);
    const double error = std::abs(area(m) - exact) / exact;
    std::printf("  sphere max_edge %.3f r: %zu triangles, area error %.4f%%\n", fraction, m.triangles.size(),
                100 * error);
    EXPECT_LT(error, previous);
    previous = error;
  }
  EXPECT_LT(previous, 0.01);
}

// However large max_edge, the normal turns by at most about
// curved_degrees_per_edge along an edge (a cell's diagonal: sqrt 2 times
// that): the area is that of the bound.
TEST(TessellateSphere, CoarseEdgesStopAtTheCurvatureBound) {
  const sphere s{vec3(0.0), 2.0, 0};
  const triangle_mesh bound = tessellate(s, s.radius);
  for (double max_edge : {1.0, 10.0, 1e6}) {
    const triangle_mesh m = tessellate(s, max_edge);
    EXPECT_EQ(m.triangles.size(), bound.triangles.size()) << max_edge;
    EXPECT_LE(largest_turn_degrees(m), std::sqrt(2.0) * curved_degrees_per_edge) << max_edge;
  }
  EXPECT_LT(std::abs(area(bound) - 4.0 * pi * 4.0) / (4.0 * pi * 4.0), 0.03);
}

TEST(TessellateSphere, ExactClosedOutwardMesh) {
  const sphere s{vec3(1.0, -2.0, 0.5), 1.7, 3};
  for (double max_edge : {5.0, 0.9, 0.2}) {
    const triangle_mesh m = tessellate(s, max_edge);
    expect_well_formed(m);
    EXPECT_TRUE(is_closed(m));
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      const vec3 r = m.positions[v] - s.center;
      ASSERT_NEAR(glm::length(r), s.radius, 1e-12 * s.radius);
      ASSERT_NEAR(glm::distance(m.normals[v], r / s.radius), 0.0, 1e-12);
      ASSERT_TRUE(m.uvs[v].x >= 0.0 && m.uvs[v].x <= 1.0 && m.uvs[v].y >= 0.0 && m.uvs[v].y <= 1.0);
    }
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const glm::ivec3& tri = m.triangles[t];
      const vec3 centroid = (m.positions[tri.x] + m.positions[tri.y] + m.positions[tri.z]) / 3.0;
      ASSERT_GT(glm::dot(triangle_cross(m, tri), centroid - s.center), 0.0) << "not counter-clockwise from outside";
      ASSERT_EQ(m.materials[t], 3);
    }
    if (max_edge < s.radius) {
      EXPECT_LE(longest_edge(m), 1.5 * max_edge);
    }
  }
}

// ---------------------------------------------------------------------------
// Quadric

quadric unit_sphere_quadric() {
  quadric q;
  q.a = q.b = q.c = 1.0;
  q.k = -1.0;
  q.box_min = vec3(-2.0);
  q.box_max = vec3(2.0);
  return q;
}

TEST(QuadricFormula, ValueAndGradientFollowTheDefinition) {
  quadric q;
  q.a = 1.5, q.b = -2.0, q.c = 0.5, q.d = 0.25, q.e = -0.75, q.f = 1.25, q.g = 0.3, q.h = -0.6, q.j = 0.9, q.k = -1.1;
  const vec3 p(0.7, -1.3, 2.1);
  const double x = p.x, y = p.y, z = p.z;
  const double expected = q.a * x * x + q.b * y * y + q.c * z * z + 2 * q.d * x * y + 2 * q.e * y * z +
                          2 * q.f * x * z + 2 * q.g * x + 2 * q.h * y + 2 * q.j * z + q.k;
  EXPECT_NEAR(quadric_value(q, p), expected, 1e-12);
  const double h = 1e-5;
  for (int i = 0; i < 3; ++i) {
    vec3 step(0.0);
    step[i] = h;
    const double numeric = (quadric_value(q, p + step) - quadric_value(q, p - step)) / (2 * h);
    EXPECT_NEAR(quadric_gradient(q, p)[i], numeric, 1e-8);
  }
}

TEST(TessellateQuadric, SphereAreaAndExactVertices) {
  const quadric q = unit_sphere_quadric();
  const double exact = 4.0 * pi;
  double previous = 1.0, finest = 1.0;
  // Edges of 0.3 and finer: coarser ones meet the curvature bound (the
  // next test). 0.075 puts grid nodes exactly on the sphere (at (+-1, 0, 0) etc).
  for (double max_edge : {0.3, 0.15, 0.075}) {
    const triangle_mesh m = tessellate(q, max_edge);
    const double error = std::abs(area(m) - exact) / exact;
    std::printf("  quadric sphere max_edge %.3f: %zu triangles, area error %.4f%%\n", max_edge, m.triangles.size(),
                100 * error);
    expect_well_formed(m);
    EXPECT_TRUE(is_closed(m));
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      ASSERT_LT(std::abs(quadric_value(q, m.positions[v])), 1e-9);
      ASSERT_NEAR(glm::distance(m.normals[v], m.positions[v]), 0.0, 1e-9) << "normal not outward";
    }
    EXPECT_LE(longest_edge(m), 1.2 * max_edge);
    EXPECT_LT(error, previous);
    previous = finest = error;
  }
  EXPECT_LT(finest, 0.02);
}

TEST(TessellateQuadric, InsideOutSphereFacesInwards) {
  quadric q = unit_sphere_quadric();
  q.a = q.b = q.c = -1.0;
  q.k = 1.0;  // positive inside: normals point to the centre
  const triangle_mesh m = tessellate(q, 0.2);
  expect_well_formed(m);
  EXPECT_TRUE(is_closed(m));
  for (std::size_t v = 0; v < m.positions.size(); ++v) ASSERT_LT(glm::dot(m.normals[v], m.positions[v]), 0.0);
}

TEST(TessellateQuadric, CylinderClippedToBox) {
  quadric q;
  q.a = q.b = 1.0;
  q.k = -1.0;
  q.box_min = vec3(-2.0, -2.0, 0.0);
  q.box_max = vec3(2.0, 2.0, 2.0);
  const double exact = 2.0 * pi * 1.0 * 2.0;
  const triangle_mesh m = tessellate(q, 0.1);
  const double error = std::abs(area(m) - exact) / exact;
  std::printf("  cylinder max_edge 0.1: %zu triangles, area error %.4f%%\n", m.triangles.size(), 100 * error);
  EXPECT_LT(error, 0.02);
  expect_well_formed(m);
  // Open only where the box cuts it.
  const edge_census census = count_edges(m);
  EXPECT_TRUE(census.oriented);
  for (const auto& [edge, uses] : census.uses) {
    ASSERT_LE(uses, 2);
    if (uses == 1) {
      const double z0 = m.positions[edge.first].z, z1 = m.positions[edge.second].z;
      ASSERT_TRUE((z0 == 0.0 && z1 == 0.0) || (z0 == 2.0 && z1 == 2.0)) << "boundary edge inside the box";
    }
  }
}

TEST(TessellateQuadric, PlaneGivesTheBoxSection) {
  for (double offset : {0.0, 0.3}) {  // 0: the plane runs through grid nodes
    quadric q;
    q.g = 0.5;  // 2 g x + k = x - offset
    q.k = -offset;
    const triangle_mesh m = tessellate(q, 0.5);
    EXPECT_NEAR(area(m), 4.0, 1e-12) << "offset " << offset;
    expect_well_formed(m);
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      ASSERT_NEAR(m.positions[v].x, offset, 1e-15);
      ASSERT_EQ(m.normals[v], vec3(1.0, 0.0, 0.0));
    }
  }
}

// The vase of the shapes scene: a hyperboloid of one sheet in a box.
quadric vase() {
  quadric q;
  q.a = 1, q.b = -0.5, q.c = 1, q.g = -1.5, q.h = 0.4, q.j = -1, q.k = 2.84;
  q.box_min = vec3(0.8, 0.0, 0.3);
  q.box_max = vec3(2.2, 1.6, 1.7);
  return q;
}

TEST(TessellateQuadric, HyperboloidIsAnOrientedManifold) {
  const quadric q = vase();
  const triangle_mesh m = tessellate(q, 0.05);
  ASSERT_GT(m.triangles.size(), 100u);
  expect_well_formed(m);
  const edge_census census = count_edges(m);
  EXPECT_TRUE(census.oriented);
  for (const auto& [edge, uses] : census.uses) ASSERT_LE(uses, 2);
  for (const vec3& p : m.positions) ASSERT_LT(std::abs(quadric_value(q, p)), 1e-9);
}

// A small ball in a huge box: at the box's scale it falls between the grid
// nodes and vanished; it is tessellated at its own scale instead.
TEST(TessellateQuadric, SmallSphereInAHugeBoxIsNotLost) {
  quadric q;
  q.a = q.b = q.c = 1.0;
  q.g = -0.5;         // centre (0.5, 0, 0)
  q.k = 0.25 - 0.04;  // radius 0.2
  q.box_min = vec3(-1e6);
  q.box_max = vec3(1e6);
  for (double max_edge : {1e5, 1.0}) {
    const triangle_mesh m = tessellate(q, max_edge);
    ASSERT_GT(m.triangles.size(), 20u) << max_edge;
    expect_well_formed(m);
    EXPECT_TRUE(is_closed(m));
    for (const vec3& p : m.positions) ASSERT_LT(std::abs(quadric_value(q, p)), 1e-9);
    EXPECT_GT(area(m), 0.5 * 4.0 * pi * 0.04);
    const double estimate = static_cast<double>(estimate_triangles(surface{"s", "", q}, max_edge));
    EXPECT_GE(estimate, 0.5 * m.triangles.size());
    EXPECT_LE(estimate, 2.0 * m.triangles.size());
  }
  // An elliptic cylinder along z (z absent from the polynomial), thin in x
  // and y: bounded across, so found too; the box still clips it in z.
  quadric cylinder;
  cylinder.a = 1.0;
  cylinder.b = 4.0;
  cylinder.k = -0.01;
  cylinder.box_min = vec3(-1e4, -1e4, -1.0);
  cylinder.box_max = vec3(1e4, 1e4, 1.0);
  const triangle_mesh m = tessellate(cylinder, 1e3);
  ASSERT_GT(m.triangles.size(), 20u);
  for (const vec3& p : m.positions) ASSERT_LE(std::abs(p.z), 1.0);
}

// A grid coarse for the surface is made finer where it bends, down to a
// sixth of the cell per axis: a cone's apex (curvature without bound)
// cannot ask for more.
TEST(TessellateQuadric, CoarseGridsBendWithTheSurface) {
  const quadric ball = unit_sphere_quadric();
  const triangle_mesh m = tessellate(ball, 100.0);
  std::printf("  unit sphere at max edge 100: %zu triangles, largest turn %.1f degrees\n", m.triangles.size(),
              largest_turn_degrees(m));
  EXPECT_LE(largest_turn_degrees(m), 1.6 * curved_degrees_per_edge);
  EXPECT_LT(std::abs(area(m) - 4.0 * pi) / (4.0 * pi), 0.02);
  quadric cone;  // x^2 + z^2 = y^2
  cone.a = cone.c = 1.0;
  cone.b = -1.0;
  const triangle_mesh by_size = tessellate(cone, 2.0), bent = tessellate(cone, 100.0);
  std::printf("  cone: %zu triangles at max edge 2, %zu at 100\n", by_size.triangles.size(), bent.triangles.size());
  EXPECT_GT(bent.triangles.size(), 0u);
  EXPECT_LE(bent.triangles.size(), 6u * 6u * by_size.triangles.size());
  expect_well_formed(bent);
}

// ---------------------------------------------------------------------------
// Bezier

std::array<vec3, 16> wavy_patch() {
  std::array<vec3, 16> c;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) c[4 * i + j] = vec3(j + 0.2 * i, i - 0.1 * j * j, std::sin(1.0 + i * j));
  return c;
}

TEST(Bezier, InterpolatesCornerControlPoints) {
  const std::array<vec3, 16> c = wavy_patch();
  EXPECT_EQ(bezier_point(c, 0, 0), c[0]);
  EXPECT_EQ(bezier_point(c, 1, 0), c[3]);  // u runs along a row
  EXPECT_EQ(bezier_point(c, 0, 1), c[12]);
  EXPECT_EQ(bezier_point(c, 1, 1), c[15]);
}

TEST(Bezier, LinearPrecision) {
  std::array<vec3, 16> c;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) c[4 * i + j] = vec3(j / 3.0, i / 3.0, 0.0);
  for (double u : {0.0, 0.1, 0.37, 0.5, 0.9, 1.0})
    for (double v : {0.0, 0.25, 0.61, 1.0}) {
      EXPECT_NEAR(glm::distance(bezier_point(c, u, v), vec3(u, v, 0.0)), 0.0, 1e-15);
      EXPECT_NEAR(glm::distance(bezier_normal(c, u, v), vec3(0.0, 0.0, 1.0)), 0.0, 1e-15);
    }
}

TEST(Bezier, FlatControlGridGivesFlatMesh) {
  bezier_surface b;
  std::array<vec3, 16> c;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) c[4 * i + j] = vec3(j + 0.3 * std::sin(i + j), i + 0.2 * j * j, 0.0);
  b.patches.push_back(c);
  const triangle_mesh m = tessellate(b, 0.3);
  expect_well_formed(m);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    ASSERT_EQ(m.positions[v].z, 0.0);
    ASSERT_EQ(std::abs(m.normals[v].z), 1.0);
  }
}

TEST(TessellateBezier, VerticesLieOnThePatch) {
  bezier_surface b;
  b.patches.push_back(wavy_patch());
  b.material = 2;
  const double max_edge = 0.25;
  const triangle_mesh m = tessellate(b, max_edge);
  expect_well_formed(m);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const vec2 uv = m.uvs[v];
    ASSERT_TRUE(uv.x >= 0 && uv.x <= 1 && uv.y >= 0 && uv.y <= 1);
    ASSERT_NEAR(glm::distance(m.positions[v], bezier_point(b.patches[0], uv.x, uv.y)), 0.0, 1e-12);
    ASSERT_NEAR(glm::distance(m.normals[v], bezier_normal(b.patches[0], uv.x, uv.y)), 0.0, 1e-12);
  }
  EXPECT_LE(longest_edge(m), 1.5 * max_edge);
  for (int material : m.materials) ASSERT_EQ(material, 2);
}

// A dome of four patches around the y axis... here the z axis: each patch
// spans a quarter turn, from the rim (row 0, z = 0) to the pole (row 3,
// every control point at (0, 0, 1): a collapsed edge, as on the teapot's lid).
bezier_surface dome() {
  const double k = 0.5522847498;  // quarter circle as a cubic
  const double radius[4] = {1.0, 1.0, 0.5, 0.0}, height[4] = {0.0, 0.5, 1.0, 1.0};
  const vec2 arc[4] = {{1, 0}, {1, k}, {k, 1}, {0, 1}};
  const vec2 turn[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};  // exact quarter turns
  bezier_surface b;
  for (const vec2& r : turn) {
    std::array<vec3, 16> c;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const vec2 a = radius[i] * arc[j];
        c[4 * i + j] = vec3(r.x * a.x - r.y * a.y, r.y * a.x + r.x * a.y, height[i]);
      }
    b.patches.push_back(c);
  }
  return b;
}

// However large max_edge, a patch is cut where it turns: the dome's
// quarter turns get edges of at most about curved_degrees_per_edge.
TEST(TessellateBezier, CoarseEdgesBendWithThePatch) {
  const triangle_mesh m = tessellate(dome(), 100.0);
  std::printf("  dome at max edge 100: %zu triangles, largest turn %.1f degrees\n", m.triangles.size(),
              largest_turn_degrees(m));
  EXPECT_LE(largest_turn_degrees(m), 1.1 * std::sqrt(2.0) * curved_degrees_per_edge);
}

TEST(TessellateBezier, PatchesAndPoleAreWelded) {
  const bezier_surface b = dome();
  EXPECT_NEAR(glm::distance(bezier_normal(b.patches[0], 0.3, 1.0), vec3(0, 0, 1)), 0.0, 1e-5);
  for (double max_edge : {1.0, 0.2, 0.05}) {
    const triangle_mesh m = tessellate(b, max_edge);
    expect_well_formed(m);
    int at_pole = 0;
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      if (glm::distance(m.positions[v], vec3(0, 0, 1)) < 1e-12) {
        ++at_pole;
        EXPECT_NEAR(glm::distance(m.normals[v], vec3(0, 0, 1)), 0.0, 1e-5);
      }
      ASSERT_GE(m.normals[v].z, -1e-12);
    }
    EXPECT_EQ(at_pole, 1);
    // One piece: every edge inside, except the rim's, is shared by two triangles.
    const edge_census census = count_edges(m);
    EXPECT_TRUE(census.oriented);
    for (const auto& [edge, uses] : census.uses) {
      ASSERT_LE(uses, 2);
      if (uses == 1) {
        ASSERT_TRUE(m.positions[edge.first].z == 0.0 && m.positions[edge.second].z == 0.0);
      }
    }
  }
}

// ---------------------------------------------------------------------------
// B-spline

bspline_surface bspline_grid(int rows, int cols, auto point) {
  bspline_surface b;
  b.rows = rows;
  b.cols = cols;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) b.control.push_back(point(r, c));
  return b;
}

bspline_surface wavy_bspline() {
  return bspline_grid(6, 7, [](int r, int c) { return vec3(0.5 * c, 0.4 * r, 0.3 * std::sin(1.7 * r + 2.3 * c)); });
}

TEST(BSpline, PartitionOfUnity) {
  const vec3 c(1.25, -3.5, 7.0);
  const bspline_surface b = bspline_grid(5, 6, [&](int, int) { return c; });
  for (double u : {0.0, 0.3, 1.0, 1.5, 2.0, 2.999, 3.0})
    for (double v : {0.0, 0.5, 1.0, 2.0})
      ASSERT_NEAR(glm::distance(bspline_point(b, u, v), c), 0.0, 1e-14) << u << " " << v;
}

TEST(BSpline, LinearPrecisionWithParameterOffset) {
  const vec3 origin(0.5, -1.0, 2.0), ex(0.3, 0.1, -0.2), ey(-0.1, 0.4, 0.25);
  const auto linear = [&](double x, double y) { return origin + x * ex + y * ey; };
  const bspline_surface b = bspline_grid(6, 5, [&](int r, int c) { return linear(c, r); });
  // Uniform cubic B-splines reproduce linear data shifted by one index.
  for (double u : {0.0, 0.4, 1.0, 1.75, 2.0})
    for (double v : {0.0, 0.2, 1.0, 2.5, 3.0}) {
      ASSERT_NEAR(glm::distance(bspline_point(b, u, v), linear(u + 1, v + 1)), 0.0, 1e-14);
      ASSERT_NEAR(glm::distance(bspline_normal(b, u, v), glm::normalize(glm::cross(ex, ey))), 0.0, 1e-14);
    }
}

TEST(BSpline, ContinuousAcrossSpans) {
  const bspline_surface b = wavy_bspline();
  const double eps = 1e-9;
  for (double v : {0.3, 1.0, 2.6})
    for (double u : {1.0, 2.0, 3.0}) {
      EXPECT_NEAR(glm::distance(bspline_point(b, u - eps, v), bspline_point(b, u + eps, v)), 0.0, 1e-8);
      EXPECT_NEAR(glm::distance(bspline_point(b, v, u - eps), bspline_point(b, v, u + eps)), 0.0, 1e-8);
      EXPECT_NEAR(glm::distance(bspline_normal(b, u - eps, v), bspline_normal(b, u + eps, v)), 0.0, 1e-7);
    }
  // The end of the last span belongs to it.
  EXPECT_NEAR(glm::distance(bspline_point(b, 4.0, 3.0), bspline_point(b, 4.0 - eps, 3.0 - eps)), 0.0, 1e-8);
}

TEST(TessellateBSpline, VerticesLieOnTheSurface) {
  const bspline_surface b = wavy_bspline();
  const double max_edge = 0.1;
  const triangle_mesh m = tessellate(b, max_edge);
  expect_well_formed(m);
  const vec2 spans(b.cols - 3, b.rows - 3);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const vec2 uv = m.uvs[v] * spans;
    ASSERT_NEAR(glm::distance(m.positions[v], bspline_point(b, uv.x, uv.y)), 0.0, 1e-12);
    ASSERT_NEAR(glm::distance(m.normals[v], bspline_normal(b, uv.x, uv.y)), 0.0, 1e-12);
  }
  EXPECT_LE(longest_edge(m), 1.5 * max_edge);
  const edge_census census = count_edges(m);
  EXPECT_TRUE(census.oriented);
  for (const auto& [edge, uses] : census.uses) ASSERT_LE(uses, 2);
}

TEST(TessellateBSpline, CoarseEdgesBendWithTheSurface) {
  const triangle_mesh m = tessellate(wavy_bspline(), 100.0);
  std::printf("  wavy B-spline at max edge 100: %zu triangles, largest turn %.1f degrees\n", m.triangles.size(),
              largest_turn_degrees(m));
  EXPECT_LE(largest_turn_degrees(m), 1.1 * std::sqrt(2.0) * curved_degrees_per_edge);
}

// ---------------------------------------------------------------------------
// Polygon faces

// A 2D polygon placed in a tilted plane; returns the plane's normal.
vec3 place_tilted(polygon_mesh& mesh, const std::vector<vec2>& corners) {
  const vec3 e1 = glm::normalize(vec3(1.0, 2.0, 0.5));
  const vec3 e2 = glm::normalize(glm::cross(vec3(0.3, -0.2, 1.0), e1));
  polygon_face face;
  for (const vec2& c : corners) {
    face.position.push_back(static_cast<int>(mesh.positions.size()));
    mesh.positions.push_back(vec3(5.0, -3.0, 2.0) + c.x * e1 + c.y * e2);
  }
  mesh.faces.push_back(face);
  return glm::cross(e1, e2);
}

void expect_exact_triangulation(const std::vector<vec2>& corners, double expected_area) {
  polygon_mesh mesh;
  double signed_area = 0.0;  // positive when counter-clockwise in 2D
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const vec2 a = corners[i], b = corners[(i + 1) % corners.size()];
    signed_area += 0.5 * (a.x * b.y - b.x * a.y);
  }
  const vec3 normal = std::copysign(1.0, signed_area) * place_tilted(mesh, corners);
  std::size_t dropped = 99;
  const triangle_mesh m = triangulate(mesh, &dropped);
  EXPECT_EQ(dropped, 0u);
  ASSERT_EQ(m.triangles.size(), corners.size() - 2);
  EXPECT_EQ(m.positions.size(), corners.size());  // one flat face shares its vertices
  EXPECT_NEAR(area(m), expected_area, 1e-12 * expected_area);
  for (const glm::ivec3& t : m.triangles) ASSERT_GT(glm::dot(triangle_cross(m, t), normal), 0.0);
  for (const vec3& n : m.normals) ASSERT_NEAR(glm::distance(n, normal), 0.0, 1e-12);
}

TEST(Triangulate, NonConvexLShapeKeepsAreaAndWinding) {
  const std::vector<vec2> l_shape = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  expect_exact_triangulation(l_shape, 3.0);
  // The same shape clockwise: its Newell normal flips, and so do the triangles.
  expect_exact_triangulation({{0, 0}, {0, 2}, {1, 2}, {1, 1}, {2, 1}, {2, 0}}, 3.0);
}

TEST(Triangulate, StarKeepsArea) {
  std::vector<vec2> star;
  for (int i = 0; i < 10; ++i) {
    const double r = i % 2 ? 0.4 : 1.0, angle = 2 * pi * i / 10;
    star.emplace_back(r * std::cos(angle), r * std::sin(angle));
  }
  expect_exact_triangulation(star, 5 * 1.0 * 0.4 * std::sin(pi / 5));
}

// A comb: half its corners reflex, the case ear clipping finds hardest.
// Every ear is checked against them; the area and the winding must hold.
TEST(Triangulate, CombWithThousandsOfReflexCornersKeepsArea) {
  polygon_mesh mesh;
  polygon_face face;
  const int teeth = 2000;
  for (int t = 0; t < teeth; ++t) {  // right to left along the top
    const double x = teeth - t;
    for (const vec2& c : {vec2(x, 1.0), vec2(x - 0.5, 1.0), vec2(x - 0.5, 0.1), vec2(x - 1.0, 0.1)})
      mesh.positions.emplace_back(c.x, c.y, 0.0);
  }
  mesh.positions.emplace_back(0.0, -1.0, 0.0);
  mesh.positions.emplace_back(teeth, -1.0, 0.0);
  for (int i = 0; i < static_cast<int>(mesh.positions.size()); ++i) face.position.push_back(i);
  mesh.faces.push_back(face);
  const triangle_mesh m = triangulate(mesh);
  EXPECT_EQ(m.triangles.size(), mesh.positions.size() - 2);
  // Teeth 0.5 x 0.9 each, on a spine 1.1 high.
  EXPECT_NEAR(area(m), teeth * (0.5 * 0.9 + 1.1), 1e-6);
  for (const glm::ivec3& t : m.triangles) ASSERT_GT(triangle_cross(m, t).z, 0.0);
}

TEST(Triangulate, RepeatedCornersCollapse) {
  polygon_mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.faces.push_back({{0, 1, 1, 2}, {}, {}, 0, 0});
  mesh.faces.push_back({{0, 1, 2, 0}, {}, {}, 0, 0});
  std::size_t dropped = 99;
  const triangle_mesh m = triangulate(mesh, &dropped);
  EXPECT_EQ(dropped, 0u);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_NEAR(area(m), 1.0, 1e-15);
  expect_well_formed(m);
}

TEST(Triangulate, DegenerateFacesAreDroppedAndCounted) {
  polygon_mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  mesh.faces.push_back({{0, 1, 2}, {}, {}, 0, 0});     // collinear
  mesh.faces.push_back({{0, 1}, {}, {}, 0, 0});        // two corners
  mesh.faces.push_back({{0, 1, 1, 0}, {}, {}, 0, 0});  // two distinct corners
  mesh.faces.push_back({{0, 1, 3}, {}, {}, 5, 0});     // fine
  std::size_t dropped = 0;
  const triangle_mesh m = triangulate(mesh, &dropped);
  EXPECT_EQ(dropped, 3u);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.materials[0], 5);
  EXPECT_EQ(triangulate(mesh).triangles.size(), 1u);  // dropped is optional
}

TEST(Triangulate, UsesGivenNormalsAndUvs) {
  polygon_mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.normals = {{0, 0, 2}, {0, 1, 1}};  // not unit: normalised
  mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.faces.push_back({{0, 1, 2, 3}, {0, 0, 1, 1}, {0, 1, 2, 3}, 4, 7});
  const triangle_mesh m = triangulate(mesh);
  ASSERT_EQ(m.triangles.size(), 2u);
  ASSERT_EQ(m.positions.size(), 4u);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const vec3 p = m.positions[v];
    const vec3 expected = p.y == 0.0 ? vec3(0, 0, 1) : glm::normalize(vec3(0, 1, 1));
    EXPECT_NEAR(glm::distance(m.normals[v], expected), 0.0, 1e-15);
    EXPECT_EQ(m.uvs[v], vec2(p.x, p.y));
  }
  for (int material : m.materials) EXPECT_EQ(material, 4);
}

TEST(Triangulate, FacesWithOwnNormalsDoNotShareVertices) {
  polygon_mesh mesh;  // a unit cube, faces counter-clockwise from outside
  for (int i = 0; i < 8; ++i) mesh.positions.push_back(vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1) - vec3(0.5));
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) mesh.faces.push_back({{f[0], f[1], f[2], f[3]}, {}, {}, 0, 0});
  const triangle_mesh m = triangulate(mesh);
  EXPECT_EQ(m.positions.size(), 24u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_NEAR(area(m), 6.0, 1e-15);
  expect_well_formed(m);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const vec3 n = m.normals[v];
    EXPECT_NEAR(glm::dot(n, m.positions[v]), 0.5, 1e-15);  // axis-aligned, outward
  }
}

// ---------------------------------------------------------------------------
// Dispatch and estimates

surface named(const std::string& name, shape geometry) {
  surface s;
  s.name = name;
  s.geometry = std::move(geometry);
  return s;
}

polygon_mesh one_square_one_sliver() {
  polygon_mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
  mesh.faces.push_back({{0, 1, 2, 3}, {}, {}, 0, 0});
  mesh.faces.push_back({{0, 1, 4}, {}, {}, 0, 0});
  return mesh;
}

TEST(TessellateSurface, DispatchesOnShape) {
  std::size_t dropped = 99;
  const triangle_mesh square = tessellate(named("square", one_square_one_sliver()), 0.1, &dropped);
  EXPECT_EQ(square.triangles.size(), 2u);
  EXPECT_EQ(dropped, 1u);
  const sphere s{vec3(0.0), 2.0, 1};
  const triangle_mesh ball = tessellate(named("ball", s), 0.3, &dropped);
  EXPECT_EQ(dropped, 0u);
  EXPECT_EQ(ball.positions, tessellate(s, 0.3).positions);
}

std::vector<std::pair<surface, double>> every_shape() {
  return {{named("polygons", one_square_one_sliver()), 0.1},
          {named("sphere", sphere{vec3(0.0), 2.0, 0}), 0.05},
          {named("quadric sphere", unit_sphere_quadric()), 0.3},
          {named("quadric sphere fine", unit_sphere_quadric()), 0.04},
          {named("vase", vase()), 0.02},
          {named("wavy patch", bezier_surface{{wavy_patch()}, 0}), 0.1},
          {named("dome", dome()), 0.03},
          {named("b-spline", wavy_bspline()), 0.05}};
}

TEST(EstimateTriangles, WithinFactorTwoOfTheRealCount) {
  for (const auto& [s, max_edge] : every_shape()) {
    const double real = static_cast<double>(tessellate(s, max_edge).triangles.size());
    const double estimate = static_cast<double>(estimate_triangles(s, max_edge));
    std::printf("  %s: %.0f triangles, estimate %.0f\n", s.name.c_str(), real, estimate);
    EXPECT_GE(estimate, 0.5 * real) << s.name;
    EXPECT_LE(estimate, 2.0 * real) << s.name;
  }
}

TEST(EstimateTriangles, TinyMaxEdgeNeitherOverflowsNorHangs) {
  for (const auto& [s, ignored] : every_shape()) {
    const std::size_t n = estimate_triangles(s, 1e-12);
    std::printf("  %s at 1e-12: estimate %zu\n", s.name.c_str(), n);
    if (!std::holds_alternative<polygon_mesh>(s.geometry)) {
      EXPECT_GT(n, 100000u) << s.name;
    }
  }
}

#ifndef NDEBUG
TEST(TessellateDeathTest, NonPositiveMaxEdgeIsAProgrammingError) {
  EXPECT_DEATH(tessellate(sphere{}, 0.0), "");
  EXPECT_DEATH(estimate_triangles(named("s", sphere{}), -1.0), "");
}
#endif

}  // namespace
}  // namespace bounce
