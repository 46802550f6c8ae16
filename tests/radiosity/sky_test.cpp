// The sky (scene.h's sky_light) against its closed forms: an open plane
// under a uniform sky of radiance L has B = rho pi L, under a gradient
// B = rho (pi h + 2 pi / 3 (z - h)); the solvers and the tracers agree.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh_builders.h"
#include "radiosity/solver.h"
#include "scene/camera_math.h"
#include "scene/scene_io.h"
#include "scene/sky.h"
#include "test_files.h"
#include "trace/ray_tracer.h"

namespace bounce {
namespace {

using std::numbers::pi;
using test_support::add_material;
using test_support::add_polygon;
using test_support::mesh_of;

// A 2 x 2 floor facing +y, nothing else: it sees the whole upper sky.
scene open_floor(const sky_light& sky, double rho = 0.5) {
  scene s;
  const int m = add_material(s, rgb(rho));
  add_polygon(s, {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, m);
  s.sky = sky;
  s.view.eye = {0, 3, 0.01};
  s.view.target = {0, 0, 0};
  s.view.fov_y_degrees = 90;
  s.view.width = s.view.height = 16;
  return s;
}

sky_light uniform_sky(rgb radiance) {
  sky_light sky;
  sky.zenith = sky.horizon = radiance;
  return sky;
}

radiosity_params params_for(solver_method method) {
  radiosity_params p;
  p.method = method;
  return p;
}

// Solves with `method` to a remaining fraction of 1e-9 (at most 400 steps).
std::unique_ptr<radiosity_solver> solve(const scene& s, const patch_mesh& mesh, solver_method method) {
  auto solver = make_radiosity_solver(s, mesh, params_for(method));
  stop_criterion stop;
  stop.remaining = 1e-9;
  stop.max_steps = 400;
  run_solver(*solver, stop);
  return solver;
}

TEST(Sky, UniformSkyOverAnOpenPlaneGivesRhoPiL) {
  const rgb radiance(2.0, 1.0, 0.5);
  const scene s = open_floor(uniform_sky(radiance), 0.5);
  const patch_mesh mesh = mesh_of(s, 0.5);
  for (const solver_method method : {solver_method::progressive, solver_method::hierarchical}) {
    const auto solver = solve(s, mesh, method);
    const auto solution = make_snapshot(*solver);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(solution->radiosity[v][c], 0.5 * pi * radiance[c], 1e-12) << name_of(method) << " vertex " << v;
    // All of it came straight from the sky; the progressive solver's power balances.
    EXPECT_EQ(solution->direct, solution->radiosity) << name_of(method);
    if (method == solver_method::progressive) {
      EXPECT_LT(balance_error(progressive_of(*solver)->balance), 1e-9);
    }
  }
}

TEST(Sky, GradientSkyMatchesItsClosedForm) {
  sky_light sky;
  sky.zenith = rgb(3.0);
  sky.horizon = rgb(0.5);
  EXPECT_NEAR(open_sky_irradiance(sky).r, pi * 0.5 + 2.0 * pi / 3.0 * 2.5, 1e-12);
  const scene s = open_floor(sky, 0.6);
  const patch_mesh mesh = mesh_of(s, 0.5);
  const double expected = 0.6 * open_sky_irradiance(sky).g;
  for (const solver_method method : {solver_method::progressive, solver_method::hierarchical}) {
    const auto solver = solve(s, mesh, method);
    const auto solution = make_snapshot(*solver);
    // 64 stratified, cosine-weighted rays per point: the mean is within 1%.
    double mean = 0.0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      EXPECT_NEAR(solution->radiosity[v].g, expected, 0.02 * expected) << name_of(method) << " vertex " << v;
      mean += solution->radiosity[v].g / double(mesh.vertex_count());
    }
    EXPECT_NEAR(mean, expected, 0.005 * expected) << name_of(method);
  }
}

// A roof over half the floor shades it: the sky is occluded like any light,
// and what the roof sends back down is the solvers' usual business.
TEST(Sky, ARoofShadesTheFloorBelowIt) {
  scene s = open_floor(uniform_sky(rgb(1.0)), 0.5);
  const int roof = add_material(s, rgb(0.5));
  add_polygon(s, {{-1, 0.2, -1}, {0, 0.2, -1}, {0, 0.2, 1}, {-1, 0.2, 1}}, roof);  // faces -y
  const patch_mesh mesh = mesh_of(s, 0.25);
  for (const solver_method method : {solver_method::progressive, solver_method::hierarchical}) {
    const auto solver = solve(s, mesh, method);
    const auto solution = make_snapshot(*solver);
    double shaded = INFINITY, open = 0.0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const vec3 p = mesh.positions[v];
      if (mesh.normals[v].y < 0.5 || p.y > 0.1) continue;  // floor vertices only
      if (p.x < -0.6 && std::abs(p.z) < 0.5) shaded = std::min(shaded, solution->radiosity[v].r);
      if (p.x > 0.6 && std::abs(p.z) < 0.5) open = std::max(open, solution->radiosity[v].r);
    }
    EXPECT_LT(shaded, 0.5 * open) << name_of(method);
    // Away from the roof, close to the open-sky value (the roof's underside,
    // lit by the sky below the horizon, adds a little).
    EXPECT_NEAR(open, 0.5 * pi, 0.02 * 0.5 * pi) << name_of(method);
    if (method == solver_method::progressive) {
      EXPECT_LT(balance_error(progressive_of(*solver)->balance), 1e-6);
    }
  }
}

// The tracers see the sky where rays leave, and light the floor with it:
// Whitted by shadow rays, the path tracer by its bounces. Both give rho L.
TEST(Sky, TracersSeeTheSkyAndLightWithIt) {
  sky_light sky;
  sky.zenith = rgb(2.0);
  sky.horizon = rgb(1.0);
  scene gradient = open_floor(sky, 0.5);
  gradient.view.eye = {0, 0.8, 1.6};  // looking at the floor and the sky beyond it
  gradient.view.target = {0, 0, -0.3};
  const ray_scene rays(gradient);
  trace_params p;
  p.diffuse = diffuse_source::ambient;  // no radiosity: the sky's light is traced
  p.light_samples = 256;
  const image whitted = trace_image(gradient, gradient.view, rays, nullptr, p);
  p.method = integrator::path;
  p.spp = 64;
  const image path = trace_image(gradient, gradient.view, rays, nullptr, p);
  const double floor_expected = 0.5 / pi * open_sky_irradiance(sky).r;
  int floor_pixels = 0, sky_pixels = 0;
  for (int y = 0; y < whitted.height; ++y)
    for (int x = 0; x < whitted.width; ++x) {
      const vec3 d = camera_ray_direction(gradient.view, x + 0.5, y + 0.5);
      const double t = d.y < 0.0 ? -gradient.view.eye.y / d.y : INFINITY;
      const vec3 hit = gradient.view.eye + t * d;
      if (std::isfinite(t) && std::abs(hit.x) < 0.95 && std::abs(hit.z) < 0.95) {
        ++floor_pixels;
        EXPECT_NEAR(whitted.at(x, y).r, floor_expected, 0.02 * floor_expected) << x << "," << y;
        EXPECT_NEAR(path.at(x, y).r, floor_expected, 0.1 * floor_expected) << x << "," << y;
      } else if (!std::isfinite(t) || std::abs(hit.x) > 1.05 || std::abs(hit.z) > 1.05) {
        ++sky_pixels;
        EXPECT_NEAR(whitted.at(x, y).r, sky_radiance(sky, d).r, 1e-6) << x << "," << y;
      }
    }
  EXPECT_GT(floor_pixels, 20);
  EXPECT_GT(sky_pixels, 20);
}

TEST(Sky, SceneFilesDescribeItAndBareModelsGetOne) {
  test_support::scratch_dir dir;
  const std::string floor = R"("materials": {"white": {"rho": [0.5, 0.5, 0.5]}},
    "surfaces": [{"polygon": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]], "material": "white"}])";
  scene s;
  load_report report;
  ASSERT_TRUE(load_scene(dir.write("u.json", "{" + floor + R"(, "sky": {"radiance": [1, 2, 3]}})"), s, report))
      << report.error;
  EXPECT_EQ(s.sky.zenith, rgb(1, 2, 3));
  EXPECT_EQ(s.sky.horizon, rgb(1, 2, 3));
  ASSERT_TRUE(load_scene(dir.write("g.json", "{" + floor + R"(, "sky": {"zenith": [2, 2, 2], "horizon": [1, 1, 1],
      "up": [0, 0, 1]}})"),
                         s, report))
      << report.error;
  EXPECT_EQ(s.sky.up, vec3(0, 0, 1));
  for (const auto& [sky, message] : std::vector<std::pair<std::string, std::string>>{
           {R"({"radiance": [1, 1, 1], "zenith": [1, 1, 1]})", "needs either 'radiance'"},
           {R"({"zenith": [1, 1, 1]})", "needs both 'zenith' and 'horizon'"},
           {R"({"radiance": [-1, 1, 1]})", "sky: radiance must be finite and >= 0"},
           {R"({"radiance": [1, 1, 1], "up": [0, 0, 0]})", "sky.up"},
           {R"({"radiance": [1, 1, 1], "colour": 2})", "unknown key 'colour'"}}) {
    load_report bad;
    EXPECT_FALSE(load_scene(dir.write("bad.json", "{" + floor + ", \"sky\": " + sky + "}"), s, bad)) << sky;
    EXPECT_NE(bad.error.find(message), std::string::npos) << bad.error;
    EXPECT_NE(bad.error.find("bad.json"), std::string::npos) << bad.error;
  }
  // A bare OBJ without an emitter opens under a white sky, saying so; one
  // with an emitter does not get one.
  load_report bare;
  ASSERT_TRUE(load_scene(dir.write("bare.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nf 1 3 2\n"), s, bare)) << bare.error;
  EXPECT_TRUE(s.sky.on());
  EXPECT_EQ(s.sky.zenith, rgb(1.0));
  bool said = false;
  for (const std::string& w : bare.warnings) said |= w.find("lit by a uniform white sky") != std::string::npos;
  EXPECT_TRUE(said);
  dir.write("lamp.mtl", "newmtl lamp\nKd 0 0 0\nKe 5 5 5\n");
  ASSERT_TRUE(
      load_scene(dir.write("lamp.obj", "mtllib lamp.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nusemtl lamp\nf 1 3 2\n"), s, bare))
      << bare.error;
  EXPECT_FALSE(s.sky.on());
}

}  // namespace
}  // namespace bounce
