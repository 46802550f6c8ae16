// Spot lights and suns (scene.h's punctual_light) against their closed
// forms in every solver and both tracers: a floor under a spot has
// B = rho I share cos / r^2, under a sun B = rho E cos where the sun is not
// hidden, and a planar mirror adds kr of it where the floor sees the sun in
// the mirror.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh_builders.h"
#include "radiosity/solver.h"
#include "scene/camera_math.h"
#include "scene/lights.h"
#include "trace/photon_tracing.h"
#include "trace/ray_scene.h"
#include "trace/ray_tracer.h"

namespace bounce {
namespace {

using std::numbers::pi;
using test_support::add_material;
using test_support::add_polygon;
using test_support::mesh_of;
constexpr double degree = pi / 180.0;

scene floor_scene(double half, double rho) {
  scene s;
  const int m = add_material(s, rgb(rho));
  add_polygon(s, {{-half, 0, -half}, {-half, 0, half}, {half, 0, half}, {half, 0, -half}}, m);
  s.view.eye = vec3(0, 1, 0);
  s.view.target = vec3(0, 0, 0);
  s.view.up = vec3(0, 0, 1);
  s.view.width = s.view.height = 33;
  s.view.fov_y_degrees = 120;
  return s;
}

punctual_light down_spot() {
  punctual_light l;
  l.type = light_type::spot;
  l.position = vec3(0.2, 1.5, -0.1);
  l.intensity = rgb(4.0, 6.0, 8.0);
  l.direction = vec3(0, -1, 0);
  l.inner_cone = 20 * degree;
  l.outer_cone = 35 * degree;
  return l;
}

punctual_light sun_along(vec3 direction, rgb irradiance) {
  punctual_light l;
  l.type = light_type::sun;
  l.direction = glm::normalize(direction);
  l.intensity = irradiance;
  return l;
}

std::unique_ptr<radiosity_solver> solve_with(const scene& s, const patch_mesh& mesh, solver_method method) {
  radiosity_params p;
  p.method = method;
  auto solver = make_radiosity_solver(s, mesh, p);
  stop_criterion stop;
  stop.remaining = 1e-9;
  stop.max_steps = 400;
  run_solver(*solver, stop);
  return solver;
}

TEST(SpotLight, FloorTakesTheConeInEverySolver) {
  scene s = floor_scene(2.0, 0.5);
  s.lights.push_back(down_spot());
  const patch_mesh mesh = mesh_of(s, 0.25);
  for (const solver_method method : {solver_method::progressive, solver_method::hierarchical}) {
    const auto solver = solve_with(s, mesh, method);
    const patch_mesh& solved = solved_mesh(*solver);
    const auto solution = make_snapshot(*solver);
    int inside = 0, edge = 0, outside = 0;
    for (std::size_t v = 0; v < solved.vertex_count(); ++v) {
      const vec3 p = solved.positions[v];
      const vec3 to = s.lights[0].position - p;
      const double r = glm::length(to);
      const double share = cone_share(s.lights[0], -to / r);
      const double expected = 0.5 * 6.0 * share * (to.y / r) / (r * r);
      EXPECT_NEAR(solution->radiosity[v].g, expected, 1e-9 * (1.0 + expected)) << name_of(method) << " " << v;
      (share == 1.0 ? inside : share == 0.0 ? outside : edge)++;
    }
    EXPECT_GT(inside, 10);
    EXPECT_GT(edge, 10);
    EXPECT_GT(outside, 10);
  }
}

// No link carries a punctual light's light, so the hierarchical solver
// splits elements where it varies: the spot's edge ends up in small
// elements, and the linear interpolation between vertices follows it.
TEST(SpotLight, TheHierarchicalSolverSplitsElementsAlongTheConesEdge) {
  scene s = floor_scene(2.0, 0.5);
  s.lights.push_back(down_spot());
  const patch_mesh mesh = mesh_of(s, 0.5);
  const punctual_light& spot = s.lights[0];
  double error[2] = {0.0, 0.0};
  double edge_area[2] = {0.0, 0.0}, edge_elements[2] = {0.0, 0.0};
  for (const bool split : {false, true}) {
    radiosity_params p;
    p.method = solver_method::hierarchical;
    p.hierarchical.split_elements = split;
    p.hierarchical.min_edge = 0.02;
    auto solver = make_radiosity_solver(s, mesh, p);
    stop_criterion stop;
    stop.remaining = 1e-9;
    stop.max_steps = 400;
    run_solver(*solver, stop);
    const patch_mesh& solved = solved_mesh(*solver);
    const auto solution = make_snapshot(*solver);
    // At 4 points inside each element: the interpolated value against the
    // exact one, by area.
    for (std::size_t e = 0; e < solved.element_count(); ++e) {
      const glm::ivec3 t = solved.elements[e];
      for (const vec3& b : {vec3(1, 1, 1) / 3.0, vec3(4, 1, 1) / 6.0, vec3(1, 4, 1) / 6.0, vec3(1, 1, 4) / 6.0}) {
        const vec3 x = b[0] * solved.positions[t[0]] + b[1] * solved.positions[t[1]] + b[2] * solved.positions[t[2]];
        const double shown = b[0] * solution->radiosity[t[0]].g + b[1] * solution->radiosity[t[1]].g +
                             b[2] * solution->radiosity[t[2]].g;
        const vec3 to = spot.position - x;
        const double r = glm::length(to);
        const double exact = 0.5 * 6.0 * cone_share(spot, -to / r) * (to.y / r) / (r * r);
        error[split] += std::abs(shown - exact) * solved.element_areas[e] / 4.0;
      }
      const vec3 c = (solved.positions[t[0]] + solved.positions[t[1]] + solved.positions[t[2]]) / 3.0;
      const double share = cone_share(spot, glm::normalize(c - spot.position));
      if (share > 0.0 && share < 1.0) {
        edge_area[split] += solved.element_areas[e];
        ++edge_elements[split];
      }
    }
  }
  // Error integrated over the floor (16 square units; peak radiosity
  // 0.5 x 6 / 1.5^2 = 1.33): 0.29 on the input mesh, 0.0014 split.
  EXPECT_LT(error[1], 0.05 * error[0]) << error[0] << " -> " << error[1];
  // The edge's elements are smaller: 0.0625 -> 0.00015 in area.
  EXPECT_LT(edge_area[1] / edge_elements[1], 0.05 * edge_area[0] / edge_elements[0]);
}

TEST(Sun, FloorTakesECosineAndARoofCastsItsShadow) {
  scene s = floor_scene(2.0, 0.5);
  // A roof facing up, 1 above the floor: the sun, 30 degrees off the
  // vertical toward +x, puts its shadow 1 tan 30 to the +x side.
  const int roof = add_material(s, rgb(0.5));
  add_polygon(s, {{-0.5, 1, -0.5}, {-0.5, 1, 0.5}, {0.5, 1, 0.5}, {0.5, 1, -0.5}}, roof);
  s.lights.push_back(sun_along(vec3(std::sin(30 * degree), -std::cos(30 * degree), 0), rgb(2.0)));
  const double lit = 0.5 * 2.0 * std::cos(30 * degree), shift = std::tan(30 * degree);
  const patch_mesh mesh = mesh_of(s, 0.2);
  for (const solver_method method : {solver_method::progressive, solver_method::hierarchical}) {
    const auto solver = solve_with(s, mesh, method);
    const patch_mesh& solved = solved_mesh(*solver);
    const auto solution = make_snapshot(*solver);
    int shaded = 0, open = 0;
    for (std::size_t v = 0; v < solved.vertex_count(); ++v) {
      const vec3 p = solved.positions[v];
      if (p.y > 0.5) {  // the roof: lit from above
        EXPECT_NEAR(solution->direct[v].r, lit, 1e-9) << name_of(method);
        continue;
      }
      const double x = p.x - shift;
      if (std::abs(x) < 0.45 && std::abs(p.z) < 0.45) {
        EXPECT_EQ(solution->direct[v].r, 0.0) << name_of(method) << " " << v;
        ++shaded;
      } else if (std::abs(x) > 0.55 || std::abs(p.z) > 0.55) {
        EXPECT_NEAR(solution->direct[v].r, lit, 1e-9) << name_of(method) << " " << v;
        ++open;
      }
    }
    EXPECT_GT(shaded, 10);
    EXPECT_GT(open, 100);
  }
}

TEST(Sun, APlanarMirrorAddsKrOfItWhereTheFloorSeesTheSunInIt) {
  // The floor x in [-1, 1]; a mirror wall at x = 1 facing -x, 1 high; the
  // sun travels along (1, -1, 0). Seen in the mirror, the sun comes along
  // (-1, -1, 0): a floor point at x looks up toward (1, 1) and meets the
  // wall at height 1 - x, inside the mirror for x > 0.
  scene s = floor_scene(1.0, 0.5);
  material glass_free;
  glass_free.kr = rgb(0.8);
  s.materials.push_back(glass_free);
  add_polygon(s, {{1, 0, -1}, {1, 0, 1}, {1, 1, 1}, {1, 1, -1}}, int(s.materials.size()) - 1);
  s.lights.push_back(sun_along(vec3(1, -1, 0), rgb(2.0)));
  const double direct = 0.5 * 2.0 * std::sqrt(0.5);
  const patch_mesh mesh = mesh_of(s, 0.2);
  for (const solver_method method : {solver_method::progressive, solver_method::hierarchical}) {
    const auto solver = solve_with(s, mesh, method);
    const patch_mesh& solved = solved_mesh(*solver);
    const auto solution = make_snapshot(*solver);
    int doubled = 0, single = 0;
    for (std::size_t v = 0; v < solved.vertex_count(); ++v) {
      const vec3 p = solved.positions[v];
      if (p.y > 1e-9 || std::abs(p.z) > 0.8) continue;  // floor, away from the mirror's sides
      if (p.x > 0.1 && p.x < 0.9) {
        EXPECT_NEAR(solution->radiosity[v].g, direct * 1.8, 1e-6) << name_of(method) << " " << v;
        ++doubled;
      } else if (p.x < -0.1) {
        EXPECT_NEAR(solution->radiosity[v].g, direct, 1e-6) << name_of(method) << " " << v;
        ++single;
      }
    }
    EXPECT_GT(doubled, 10);
    EXPECT_GT(single, 10);
  }
}

TEST(SpotLight, WhittedAndThePathTracerSeeTheCone) {
  scene s = floor_scene(4.0, 0.6);
  s.lights.push_back(down_spot());
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  const image whitted = trace_image(s, s.view, rays, nullptr, p);
  p.method = integrator::path;
  p.spp = 16;
  const image path = trace_image(s, s.view, rays, nullptr, p);
  int inside = 0, outside = 0;
  for (int y = 0; y < whitted.height; ++y)
    for (int x = 0; x < whitted.width; ++x) {
      const vec3 d = camera_ray_direction(s.view, x + 0.5, y + 0.5);
      const vec3 point = s.view.eye + d / -d.y;
      const vec3 to = s.lights[0].position - point;
      const double r = glm::length(to);
      const double share = cone_share(s.lights[0], -to / r);
      const double expected = 0.6 / pi * 6.0 * share * (to.y / r) / (r * r);
      EXPECT_NEAR(whitted.at(x, y).g, expected, 1e-5 * (1.0 + expected)) << x << "," << y;
      // The path tracer's pixels spread over the pixel: away from the edge
      // its value is the same.
      const double a = std::acos(glm::dot(-to / r, s.lights[0].direction)) / degree;
      if (a < 18.0) {
        EXPECT_NEAR(path.at(x, y).g, expected, 0.02 * expected) << x << "," << y;
        ++inside;
      } else if (a > 37.0) {
        EXPECT_EQ(path.at(x, y).g, 0.0f) << x << "," << y;
        ++outside;
      }
    }
  EXPECT_GT(inside, 20);
  EXPECT_GT(outside, 20);
}

TEST(Sun, TracersLightTheOpenFloorAndThePhotonsCarryItsPower) {
  scene s = floor_scene(4.0, 0.6);
  s.lights.push_back(sun_along(vec3(0.3, -1, 0.2), rgb(1.5)));
  const double expected = 0.6 / pi * 1.5 * glm::dot(vec3(0, 1, 0), -s.lights[0].direction);
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  const image whitted = trace_image(s, s.view, rays, nullptr, p);
  p.method = integrator::path;
  p.spp = 4;
  const image path = trace_image(s, s.view, rays, nullptr, p);
  for (int y = 0; y < whitted.height; ++y)
    for (int x = 0; x < whitted.width; ++x) {
      EXPECT_NEAR(whitted.at(x, y).r, expected, 1e-6) << x << "," << y;
      EXPECT_NEAR(path.at(x, y).r, expected, 1e-6) << x << "," << y;
    }
  // The photons leave a disc over the scene's ball with E pi r^2; the floor
  // takes E cos times its area of it.
  photon_params pp;
  pp.photon_count = 200000;
  const caustic_result photons = caustic_photons(s, rays, pp);
  const double radius = 0.5 * std::sqrt(8.0 * 8.0 * 2.0);
  EXPECT_NEAR(photons.stats.emitted_power.r, 1.5 * pi * radius * radius, 1e-9);
  const double on_floor = 1.5 * glm::dot(vec3(0, 1, 0), -s.lights[0].direction) * 64.0;
  EXPECT_NEAR(photons.stats.direct_power.r, on_floor, 0.02 * on_floor);
  EXPECT_LT(channel_mean(photon_power_imbalance(photons.stats)), 1e-9 * photons.stats.emitted_power.r);
}

}  // namespace
}  // namespace bounce
