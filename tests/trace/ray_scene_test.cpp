// Ray queries and specular optics (docs/accuracy-and-closed-forms.md, section 8).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mesh_builders.h"
#include "scene/tessellate.h"
#include "trace/optics.h"
#include "trace/ray_scene.h"

namespace bounce {
namespace {

using std::numbers::pi;
using testing::add_closed_box;
using testing::add_material;

// Fibonacci points on the unit sphere.
std::vector<vec3> sphere_points(int n) {
  std::vector<vec3> out;
  for (int i = 0; i < n; ++i) {
    const double y = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - y * y), phi = i * pi * (3 - std::sqrt(5.0));
    out.push_back({r * std::cos(phi), y, r * std::sin(phi)});
  }
  return out;
}

TEST(RayScene, SphereHitsLandOnTheSampledPoints) {
  scene s;
  const int m = add_material(s, rgb(0.5));
  surface ball;
  ball.geometry = sphere{vec3(1, 2, 3), 0.7, m};
  s.surfaces.push_back(ball);
  ray_scene rays(s, 0.1);
  for (const vec3& n : sphere_points(500)) {
    const vec3 p = vec3(1, 2, 3) + 0.7 * n;
    // From outside along the normal, straight back at the point.
    const auto hit = rays.intersect(p + 2.0 * n, -n);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(glm::length(hit->point - p), 0.0, 1e-9);
    EXPECT_NEAR(glm::dot(hit->normal, n), 1.0, 1e-12);
    EXPECT_NEAR(hit->t, 2.0, 1e-9);
    EXPECT_EQ(hit->material, m);
    // And from an oblique direction, the first hit is still on the sphere.
    const vec3 d = glm::normalize(-n + vec3(0.3, -0.2, 0.1));
    const auto oblique = rays.intersect(p - 3.0 * d, d);
    ASSERT_TRUE(oblique);
    EXPECT_NEAR(glm::length(oblique->point - vec3(1, 2, 3)), 0.7, 1e-12);
  }
}

TEST(RayScene, QuadricHitsLandOnTheSampledPointsInsideTheBox) {
  // Cylinder x^2 + z^2 = 0.25, clipped to y in [0, 2].
  scene s;
  const int m = add_material(s, rgb(0.5));
  quadric q;
  q.a = q.c = 1;
  q.k = -0.25;
  q.box_min = vec3(-1, 0, -1);
  q.box_max = vec3(1, 2, 1);
  q.material = m;
  surface tube;
  tube.geometry = q;
  s.surfaces.push_back(tube);
  ray_scene rays(s, 0.1);
  for (int i = 0; i < 200; ++i) {
    const double angle = 2 * pi * i / 200, y = 0.05 + 1.9 * ((i * 37) % 200) / 200.0;
    const vec3 n(std::cos(angle), 0, std::sin(angle));
    const vec3 p = vec3(0, y, 0) + 0.5 * n;
    const auto hit = rays.intersect(p + 1.5 * n, -n);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(glm::length(hit->point - p), 0.0, 1e-9);
    EXPECT_NEAR(glm::dot(hit->normal, n), 1.0, 1e-9);  // the gradient points out
    EXPECT_NEAR(quadric_value(q, hit->point), 0.0, 1e-12);
  }
  // Above the box the cylinder does not exist.
  EXPECT_FALSE(rays.intersect(vec3(2, 2.5, 0), vec3(-1, 0, 0)));
  // A ray down the axis inside the tube meets nothing (open ends).
  EXPECT_FALSE(rays.intersect(vec3(0, 5, 0), vec3(0, -1, 0)));
}

TEST(RayScene, GrazingRaysAndRaysLeavingASurface) {
  scene s;
  const int m = add_material(s, rgb(0.5));
  surface ball;
  ball.geometry = sphere{vec3(0.0), 1.0, m};
  s.surfaces.push_back(ball);
  ray_scene rays(s, 0.1);
  // Tangent at the top: a hit at the tangent point or a miss, never NaN.
  const auto tangent = rays.intersect(vec3(-5, 1, 0), vec3(1, 0, 0));
  if (tangent) {
    EXPECT_TRUE(std::isfinite(tangent->t));
    EXPECT_NEAR(tangent->point.y, 1.0, 1e-6);
  }
  EXPECT_FALSE(rays.intersect(vec3(-5, 1 + 1e-6, 0), vec3(1, 0, 0)));
  const auto grazing = rays.intersect(vec3(-5, 1 - 1e-6, 0), vec3(1, 0, 0));
  ASSERT_TRUE(grazing);
  EXPECT_NEAR(glm::length(grazing->point), 1.0, 1e-12);
  // A reflected ray leaves from the hit lifted along the normal: it must
  // not find the sphere again. A refracted ray starts lifted inwards and
  // meets the far side.
  for (const vec3& n : sphere_points(200)) {
    const auto hit = rays.intersect(2.0 * n, -n);
    ASSERT_TRUE(hit);
    const double lift = rays.surface_offset();
    EXPECT_NEAR(lift, 1e-5 * 2 * std::sqrt(3.0), 1e-15);
    const vec3 out = glm::normalize(n + vec3(0.1, 0.2, -0.1));
    if (glm::dot(out, hit->normal) > 0) {
      EXPECT_FALSE(rays.intersect(hit->point + lift * hit->normal, out));
    }
    const auto through = rays.intersect(hit->point - lift * hit->normal, -n);
    ASSERT_TRUE(through);
    EXPECT_NEAR(through->t, 2.0 - lift, 1e-9);  // the diameter, less the lift
  }
}

TEST(RayScene, ClosedBoxIsWatertight) {
  // pbrt's test: rays from inside a closed mesh aimed at its vertices and
  // edges all hit it.
  scene s;
  const int m = add_material(s, rgb(0.5));
  add_closed_box(s, vec3(-1, -2, -0.5), vec3(3, 1, 2), m);
  ray_scene rays(s, 0.1);
  const vec3 lo(-1, -2, -0.5), hi(3, 1, 2);
  std::vector<vec3> targets;
  for (int i = 0; i < 8; ++i) targets.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  for (std::size_t a = 0; a < 8; ++a)
    for (std::size_t b = a + 1; b < 8; ++b)
      for (int k = 1; k < 8; ++k) targets.push_back(targets[a] + (targets[b] - targets[a]) * (k / 8.0));
  for (const vec3& origin : {vec3(0.0), vec3(1, -1, 1), vec3(2.9, 0.9, 1.9)})
    for (const vec3& target : targets)
      EXPECT_TRUE(rays.intersect(origin, glm::normalize(target - origin)))
          << "light leaks towards " << target.x << "," << target.y << "," << target.z;
}

TEST(Optics, RefractionThroughASlab) {
  // Item 10: a slab of glass (n = 1.5) of thickness d between two parallel
  // faces: the ray leaves parallel to how it came, shifted sideways by
  // d sin(t1 - t2) / cos(t2).
  const double d = 0.8;
  for (double degrees : {10.0, 35.0, 60.0, 80.0}) {
    const double t1 = glm::radians(degrees);
    const vec3 in(std::sin(t1), -std::cos(t1), 0);  // travelling down onto y = 0
    const auto inside = refract(in, vec3(0, 1, 0), 1.0, 1.5);
    ASSERT_TRUE(inside);
    const double t2 = std::asin(std::sin(t1) / 1.5);
    EXPECT_NEAR(std::acos(-inside->y), t2, 1e-12);
    // Down through the slab to y = -d, out through a face whose normal (for
    // a ray leaving it) is +y... facing against the ray: (0, 1, 0).
    const vec3 exit_point = *inside * (d / -inside->y);
    const auto out = refract(*inside, vec3(0, 1, 0), 1.5, 1.0);
    ASSERT_TRUE(out);
    EXPECT_NEAR(glm::length(*out - in), 0.0, 1e-12);  // parallel to the entry
    // Lateral offset: distance between the exit ray and the undeviated line.
    const vec3 straight = in * (d / -in.y);
    const double offset = glm::length(glm::cross(exit_point - straight, in));
    EXPECT_NEAR(offset, d * std::sin(t1 - t2) / std::cos(t2), 1e-12);
  }
}

TEST(Optics, TotalInternalReflectionAtTheCriticalAngle) {
  const double critical = std::asin(1.0 / 1.5);
  EXPECT_NEAR(glm::degrees(critical), 41.81, 0.005);
  for (double offset : {-1e-6, 1e-6}) {
    const double a = critical + offset;
    const vec3 d(std::sin(a), std::cos(a), 0);  // inside glass, going up to the face y = 0
    const auto out = refract(d, vec3(0, -1, 0), 1.5, 1.0);
    EXPECT_EQ(out.has_value(), offset < 0) << offset;
    EXPECT_EQ(fresnel_dielectric(std::cos(a), 1.5, 1.0) == 1.0, offset > 0);
  }
  // Fresnel at normal incidence: ((n1 - n2) / (n1 + n2))^2 = 0.04 for glass.
  EXPECT_NEAR(fresnel_dielectric(1.0, 1.0, 1.5), 0.04, 1e-12);
  EXPECT_NEAR(fresnel_dielectric(1.0, 1.5, 1.0), 0.04, 1e-12);
}

TEST(Optics, MirrorAt45DegreesTurnsARayByARightAngle) {
  // Item 11's geometry: a mirror at 45 degrees sends a ray along +z to +y,
  // and a second one back along -z: what is behind the camera, exactly.
  const vec3 first = reflect(vec3(0, 0, 1), glm::normalize(vec3(0, 1, -1)));
  EXPECT_NEAR(glm::length(first - vec3(0, 1, 0)), 0.0, 1e-15);
  const vec3 second = reflect(first, glm::normalize(vec3(0, -1, -1)));
  EXPECT_NEAR(glm::length(second - vec3(0, 0, -1)), 0.0, 1e-15);
  // Reflection keeps length and the angle to the normal.
  const vec3 d = glm::normalize(vec3(0.3, -0.9, 0.2)), n = glm::normalize(vec3(0.1, 1, 0));
  EXPECT_NEAR(glm::length(reflect(d, n)), 1.0, 1e-15);
  EXPECT_NEAR(glm::dot(reflect(d, n), n), -glm::dot(d, n), 1e-15);
}

}  // namespace
}  // namespace bounce
