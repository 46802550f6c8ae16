// Ray queries and specular optics (docs/accuracy-and-closed-forms.md, section 8).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "measure/ray_throughput.h"
#include "mesh_builders.h"
#include "scene/camera_math.h"
#include "scene/scene_io.h"
#include "scene/tessellate.h"
#include "test_files.h"
#include "optics/optics.h"
#include "trace/ray_scene.h"

namespace bounce {
namespace {

using std::numbers::pi;
using test_support::add_closed_box;
using test_support::add_material;
using test_support::source_path;

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

// Each packet hit is the single-ray hit of the same ray: the same surface
// and material, t and point to double round-off (both are recomputed in
// double from the same triangle or sphere), normals to float round-off
// (Embree's barycentrics). Returns how many rays hit analytic surfaces.
int expect_packets_match_single_rays(const ray_scene& rays, const scene& s, const std::vector<vec3>& origins,
                                     const std::vector<vec3>& directions, double t_min, double t_max) {
  std::vector<std::optional<ray_hit>> packets(origins.size());
  rays.intersect_packets(origins, directions, packets, t_min, t_max);
  int analytic = 0, hits = 0;
  for (std::size_t k = 0; k < origins.size(); ++k) {
    const auto single = rays.intersect(origins[k], directions[k], t_min, t_max);
    EXPECT_EQ(single.has_value(), packets[k].has_value()) << "ray " << k;
    if (!single || !packets[k]) continue;
    ++hits;
    const ray_hit& a = *single;
    const ray_hit& b = *packets[k];
    EXPECT_EQ(a.surface, b.surface) << "ray " << k;
    EXPECT_EQ(a.material, b.material) << "ray " << k;
    EXPECT_NEAR(a.t, b.t, 1e-9 * std::max(1.0, a.t)) << "ray " << k;
    EXPECT_NEAR(glm::length(a.point - b.point), 0.0, 1e-9 * std::max(1.0, a.t)) << "ray " << k;
    EXPECT_NEAR(glm::length(a.normal - b.normal), 0.0, 1e-5) << "ray " << k;
    EXPECT_NEAR(glm::length(a.face_normal - b.face_normal), 0.0, 1e-9) << "ray " << k;
    EXPECT_NEAR(glm::length(a.uv - b.uv), 0.0, 1e-5) << "ray " << k;
    const shape& g = s.surfaces[std::size_t(a.surface)].geometry;
    analytic += std::holds_alternative<sphere>(g) || std::holds_alternative<quadric>(g);
  }
  EXPECT_GT(hits, 0);
  return analytic;
}

// A 64 x 64 picture's primary rays, pixel centres row by row.
void primary_rays_64(const scene& s, std::vector<vec3>& origins, std::vector<vec3>& directions) {
  camera view = s.view;
  view.width = view.height = 64;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      origins.push_back(view.eye);
      directions.push_back(camera_ray_direction(view, x + 0.5, y + 0.5));
    }
}

TEST(RayScene, PacketsGiveTheSingleRayHitsOnTheWhittedScene) {
  scene s;
  load_report report;
  ASSERT_TRUE(load_scene(source_path("assets/whitted/whitted.json"), s, report)) << report.error;
  const ray_scene rays(s);
  std::vector<vec3> origins, directions;
  primary_rays_64(s, origins, directions);
  // The two spheres (user geometry, through the packet callback) fill a
  // good part of the picture.
  EXPECT_GT(expect_packets_match_single_rays(rays, s, origins, directions, 0.0, INFINITY), 400);
  // And the incoherent rays that bounce off what the primary rays hit.
  ray_batch primary;
  primary.origins = origins;
  primary.directions = directions;
  const ray_batch bounced = bounce_rays(rays, primary, 7);
  EXPECT_GT(bounced.origins.size(), 2000u);
  expect_packets_match_single_rays(rays, s, bounced.origins, bounced.directions, 0.0, INFINITY);
}

TEST(RayScene, PacketsGiveTheSingleRayHitsInTheCornellBox) {
  scene s;
  load_report report;
  ASSERT_TRUE(load_scene(source_path("assets/cornell_box/cornell_box.json"), s, report)) << report.error;
  const ray_scene rays(s);
  std::vector<vec3> origins, directions;
  primary_rays_64(s, origins, directions);
  expect_packets_match_single_rays(rays, s, origins, directions, 0.0, INFINITY);
}

TEST(RayScene, PartialPacketsAndQuadricsInPackets) {
  // A sphere in front of a clipped cylinder, in front of a wall; rays in
  // a fan, a count that is not a multiple of 8, and a t range that cuts
  // some of the hits off at either end.
  scene s;
  const int m = add_material(s, rgb(0.5));
  surface ball;
  ball.geometry = sphere{vec3(0.6, 0, 0), 0.5, m};
  s.surfaces.push_back(ball);
  quadric q;  // y^2 + (z - 2)^2 = 0.25, along x, clipped to x in [-1.5, 0.2]
  q.b = q.c = 1;
  q.j = -2;
  q.k = 3.75;
  q.box_min = vec3(-1.5, -1, 1);
  q.box_max = vec3(0.2, 1, 3);
  q.material = m;
  surface tube;
  tube.geometry = q;
  s.surfaces.push_back(tube);
  add_closed_box(s, vec3(-4, -4, 4), vec3(4, 4, 5), m);
  const ray_scene rays(s, 0.1);
  std::vector<vec3> origins, directions;
  for (int i = 0; i < 203; ++i) {
    const double a = -0.6 + 1.2 * i / 202.0;
    origins.push_back(vec3(0.01 * (i % 5), 0.3, -3));
    directions.push_back(glm::normalize(vec3(std::sin(a), 0.005 * (i % 7), std::cos(a))));
  }
  EXPECT_GT(expect_packets_match_single_rays(rays, s, origins, directions, 0.0, INFINITY), 50);
  EXPECT_GT(expect_packets_match_single_rays(rays, s, origins, directions, 3.2, 6.5), 10);
  // A single ray, and none.
  expect_packets_match_single_rays(rays, s, {origins[100]}, {directions[100]}, 0.0, INFINITY);
  rays.intersect_packets({}, {}, {}, 0.0);
  std::vector<std::optional<ray_hit>> two(2);
  EXPECT_THROW(rays.intersect_packets(origins, directions, two), std::invalid_argument);
}

TEST(RayScene, EmbreeQueriesOfEveryWidthAgreeWithIntersect) {
  scene s;
  load_report report;
  ASSERT_TRUE(load_scene(source_path("assets/whitted/whitted.json"), s, report)) << report.error;
  s.view.width = s.view.height = 40;
  const ray_scene rays(s);
  const ray_batch primary = primary_rays(s.view);
  ASSERT_EQ(primary.floats.size(), 1600u);
  // Tiles of 4 x 4: the 17th ray is the second tile's first pixel.
  EXPECT_NEAR(glm::length(primary.directions[16] - camera_ray_direction(s.view, 4.5, 0.5)), 0.0, 1e-15);
  EXPECT_NEAR(glm::length(primary.directions[4] - camera_ray_direction(s.view, 0.5, 1.5)), 0.0, 1e-15);
  const ray_batch bounced = bounce_rays(rays, primary, 3);
  for (const ray_batch* batch : {&primary, &bounced}) {
    // 1 to 15 rays left over past the last whole packet.
    const std::span<const float_ray> some = std::span(batch->floats).first(batch->floats.size() - 5);
    std::vector<float> t1(some.size());
    const std::size_t hits = rays.embree_closest_hits(some, 1, t1.data());
    std::size_t expected = 0;
    for (std::size_t k = 0; k < some.size(); ++k) {
      const auto hit = rays.intersect(batch->origins[k], batch->directions[k], batch->t_min);
      expected += hit.has_value();
      EXPECT_EQ(hit.has_value(), std::isfinite(t1[k])) << "ray " << k;
      if (hit) {
        EXPECT_NEAR(hit->t, t1[k], 1e-5 * hit->t) << "ray " << k;
      }
    }
    EXPECT_EQ(hits, expected);
    EXPECT_GT(hits, some.size() / 4);
    for (int width : {4, 8, 16}) {
      std::vector<float> tk(some.size());
      EXPECT_EQ(rays.embree_closest_hits(some, width, tk.data()), hits) << "width " << width;
      for (std::size_t k = 0; k < some.size(); ++k) {
        if (std::isfinite(t1[k])) {
          EXPECT_NEAR(tk[k], t1[k], 1e-5f * t1[k]) << "width " << width << ", ray " << k;
        } else {
          EXPECT_FALSE(std::isfinite(tk[k])) << "width " << width << ", ray " << k;
        }
      }
    }
  }
  EXPECT_THROW(rays.embree_closest_hits(primary.floats, 3), std::invalid_argument);
  // Every query of the bench counts the same hits on the same rays.
  const std::vector<ray_query> all = {ray_query::bounce_single,  ray_query::bounce_packets, ray_query::embree_single,
                                      ray_query::embree_packet4, ray_query::embree_packet8, ray_query::embree_packet16};
  for (const ray_rate& r : measure_ray_rates(rays, bounced, all, 1)) {
    EXPECT_EQ(r.hits, measure_ray_rates(rays, bounced, {ray_query::bounce_single}, 1).front().hits) << name_of(r.query);
    EXPECT_EQ(r.rays, bounced.origins.size());
    EXPECT_GT(r.rays_per_second, 0.0);
  }
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
