// The ray tracers (Whitted, two-pass, path), textures, emitter sampling,
// the radiosity field and the image metrics, against closed forms.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "base/random_stream.h"
#include "image/image_metrics.h"
#include "mesh_builders.h"
#include "radiosity/solver.h"
#include "scene/camera_math.h"
#include "scene/scene_io.h"
#include "scene/texture.h"
#include "test_files.h"
#include "trace/radiosity_field.h"
#include "trace/ray_tracer.h"

namespace bounce {
namespace {

using std::numbers::pi;
using test_support::add_closed_box;
using test_support::add_material;
using test_support::add_polygon;
using test_support::mesh_of;
using test_support::source_path;

scene load(const std::string& relative) {
  scene s;
  load_report report;
  EXPECT_TRUE(load_scene(source_path(relative), s, report)) << report.error;
  return s;
}

// ---- textures ----

TEST(Texture, CheckerAlternatesSquaresAndAveragesItsColours) {
  texture t;
  t.kind = texture_kind::checker;
  t.color0 = rgb(1, 0, 0);
  t.color1 = rgb(0, 0, 1);
  t.scale = 4;  // squares of 0.25
  EXPECT_EQ(texture_value(t, {0.1, 0.1}), t.color0);
  EXPECT_EQ(texture_value(t, {0.3, 0.1}), t.color1);
  EXPECT_EQ(texture_value(t, {0.3, 0.3}), t.color0);
  EXPECT_EQ(texture_value(t, {-0.1, 0.1}), t.color1);  // continues past 0
  EXPECT_EQ(texture_mean(t), rgb(0.5, 0, 0.5));
}

TEST(Texture, ImageIsBilinearRepeatsAndHasItsTopRowAtVOne) {
  texture t;
  t.kind = texture_kind::image;
  t.width = 2;
  t.height = 2;
  // Row 0 (top): black, white; row 1: red, green.
  t.texels = {0, 0, 0, 1, 1, 1, 1, 0, 0, 0, 1, 0};
  EXPECT_NEAR(texture_value(t, {0.25, 0.75}).r, 0.0, 1e-12);  // top-left texel centre
  EXPECT_NEAR(texture_value(t, {0.75, 0.75}).g, 1.0, 1e-12);  // top-right
  EXPECT_NEAR(texture_value(t, {0.25, 0.25}).r, 1.0, 1e-12);  // bottom-left: red
  EXPECT_NEAR(texture_value(t, {1.25, 0.25}).r, 1.0, 1e-12);  // repeats
  const rgb middle = texture_value(t, {0.5, 0.75});           // halfway between black and white
  EXPECT_NEAR(middle.r, 0.5, 1e-12);
  EXPECT_NEAR(texture_mean(t).g, 0.5, 1e-12);
}

TEST(Texture, SpheresAndQuadricsHaveParametersForTextures) {
  scene s;
  const int m = add_material(s, rgb(0.5));
  surface ball;
  ball.geometry = sphere{vec3(0.0), 1.0, m};
  s.surfaces.push_back(ball);
  surface tube;
  quadric cylinder;  // x^2 + z^2 = 1, 0 <= y <= 2, around x = 5
  cylinder.a = cylinder.c = 1;
  cylinder.g = -5;  // (x - 5)^2 = x^2 - 10 x + 25
  cylinder.k = 24;
  cylinder.box_min = vec3(3.9, 0, -1.1);
  cylinder.box_max = vec3(6.1, 2, 1.1);
  cylinder.material = m;
  tube.geometry = cylinder;
  s.surfaces.push_back(tube);
  const ray_scene rays(s);
  // v = 1 at the sphere's top (+y), where an image's top row goes.
  EXPECT_NEAR(rays.intersect(vec3(0, 5, 0), vec3(0, -1, 0))->uv.y, 1.0, 1e-9);
  EXPECT_NEAR(rays.intersect(vec3(0, -5, 0), vec3(0, 1, 0))->uv.y, 0.0, 1e-9);
  EXPECT_NEAR(rays.intersect(vec3(0, 0, -5), vec3(0, 0, 1))->uv.y, 0.5, 1e-9);
  // The cylinder: height in its box, angle about its axis.
  const auto side = rays.intersect(vec3(8, 1.5, 0), vec3(-1, 0, 0));
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->uv.y, 0.75, 1e-9);
  EXPECT_NEAR(side->uv.x, 0.5, 1e-9);  // angle 0 about the axis
}

// ---- emitters ----

TEST(EmitterSampling, UniformByAreaOverEveryEmitter) {
  scene s;
  const int light = add_material(s, rgb(0.0), rgb(1.0));
  const int dark = add_material(s, rgb(0.5));
  add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, light);  // area 1
  add_polygon(s, {{2, 0, 0}, {5, 0, 0}, {5, 1, 0}, {2, 1, 0}}, light);  // area 3
  add_polygon(s, {{0, 0, 1}, {9, 0, 1}, {9, 9, 1}}, dark);
  const ray_scene rays(s);
  EXPECT_NEAR(rays.emitter_area(), 4.0, 1e-12);
  EXPECT_TRUE(rays.is_sampled_emitter(0));
  EXPECT_FALSE(rays.is_sampled_emitter(2));
  // Stratified u: a quarter of the samples on the first square, their
  // mean at the areas' centroid.
  const int n = 64;
  int on_first = 0;
  vec3 mean(0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const emitter_sample e = rays.sample_emitter((i + 0.5) / n, (j + 0.5) / n);
      on_first += e.point.x < 1.5;
      mean += e.point / double(n * n);
      EXPECT_NEAR(e.pdf_area, 0.25, 1e-12);
      EXPECT_NEAR(e.normal.z, 1.0, 1e-12);
    }
  EXPECT_NEAR(on_first / double(n * n), 0.25, 0.02);
  EXPECT_NEAR(mean.x, (0.5 * 1 + 3.5 * 3) / 4.0, 0.02);
  EXPECT_NEAR(mean.y, 0.5, 0.02);
}

// ---- Whitted ----

// A diffuse floor under a point light, seen straight down.
scene lit_floor(double rho, rgb intensity, double height) {
  scene s;
  const int m = add_material(s, rgb(rho));
  add_polygon(s, {{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}}, m);
  s.lights.push_back({vec3(0, height, 0), intensity});
  s.view.eye = vec3(0, 1, 0);
  s.view.target = vec3(0, 0, 0);
  s.view.up = vec3(0, 0, 1);
  s.view.width = s.view.height = 33;
  s.view.fov_y_degrees = 60;
  return s;
}

TEST(Whitted, PointLightOnADiffusePlaneIsRhoOverPiTimesIrradiance) {
  const scene s = lit_floor(0.6, rgb(10.0), 2.0);
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  const image img = trace_image(s, s.view, rays, nullptr, p);
  for (int y = 0; y < img.height; y += 4)
    for (int x = 0; x < img.width; x += 4) {
      const vec3 d = camera_ray_direction(s.view, x + 0.5, y + 0.5);
      const vec3 point = s.view.eye + d / -d.y;  // on y = 0
      const vec3 to_light = vec3(0, 2, 0) - point;
      const double r2 = glm::dot(to_light, to_light);
      const double expected = 0.6 / pi * 10.0 * (2.0 / std::sqrt(r2)) / r2;
      EXPECT_NEAR(img.at(x, y).g, expected, 1e-6 * expected) << x << "," << y;
    }
}

TEST(Whitted, ShadowsAreBlackWithoutAmbientAndLitByIt) {
  scene s = lit_floor(0.5, rgb(10.0), 2.0);
  const int m = add_material(s, rgb(0.5));
  add_polygon(s, {{-0.5, 1.5, -0.5}, {0.5, 1.5, -0.5}, {0.5, 1.5, 0.5}, {-0.5, 1.5, 0.5}}, m);  // a roof, facing down
  s.view.eye = vec3(0, 1, 0);
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  const image dark = trace_image(s, s.view, rays, nullptr, p);
  EXPECT_EQ(dark.at(16, 16).g, 0.0f);
  p.ambient_irradiance = rgb(2.0);
  const image lit = trace_image(s, s.view, rays, nullptr, p);
  EXPECT_NEAR(lit.at(16, 16).g, 0.5 * 2.0 / pi, 1e-7);  // float pixels
}

TEST(Whitted, MirrorShowsWhatItFacesTimesKr) {
  // A mirror floor reflecting a uniform emitting ceiling: kr x Ke.
  scene s;
  const int ceiling = add_material(s, rgb(0.0), rgb(3.0));
  const int mirror = add_material(s, rgb(0.0));
  s.materials[mirror].kr = rgb(0.7);
  add_polygon(s, {{-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}}, mirror);
  add_polygon(s, {{-50, 5, -50}, {50, 5, -50}, {50, 5, 50}, {-50, 5, 50}}, ceiling);
  s.view.eye = vec3(0, 1, 0);
  s.view.target = vec3(0, 0, 0);
  s.view.up = vec3(0, 0, 1);
  s.view.width = s.view.height = 16;
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  const image img = trace_image(s, s.view, rays, nullptr, p);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) EXPECT_NEAR(img.at(x, y).r, 0.7 * 3.0, 1e-6);  // float pixels
}

TEST(Whitted, GlassSlabPassesLightWithFresnelLossesOnly) {
  // Looking down through a slab (n = 1.5, kt = 1, Fresnel) at an emitting
  // floor: two interfaces at normal incidence each transmit 1 - 0.04;
  // the reflected light sees the black sky. Depth allows the inner
  // bounces, which add (0.96 x 0.04)^2 x ... , far below 1e-3.
  scene s;
  const int floor = add_material(s, rgb(0.0), rgb(1.0));
  const int glass = add_material(s, rgb(0.0));
  s.materials[glass].kt = rgb(1.0);
  s.materials[glass].ior = 1.5;
  s.materials[glass].fresnel = true;
  add_polygon(s, {{-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}}, floor);
  add_closed_box(s, vec3(-40, 1, -40), vec3(40, 2, 40), glass);
  // add_closed_box faces inwards; the slab's outside is where light comes from: flip them.
  for (std::size_t i = 1; i < s.surfaces.size(); ++i) {
    auto& mesh = std::get<polygon_mesh>(s.surfaces[i].geometry);
    for (polygon_face& f : mesh.faces) std::reverse(f.position.begin(), f.position.end());
  }
  s.view.eye = vec3(0, 3, 0);
  s.view.target = vec3(0, 0, 0);
  s.view.up = vec3(0, 0, 1);
  s.view.width = s.view.height = 3;
  s.view.fov_y_degrees = 1;
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  p.max_depth = 20;
  const double t = 1.0 - 0.04;
  EXPECT_NEAR(trace_image(s, s.view, rays, nullptr, p).at(1, 1).r, t * t, 2e-3);
}

TEST(Whitted, SameSeedSamePictureOnAnyNumberOfThreads) {
  const scene s = load("assets/whitted/whitted.json");
  scene small = s;
  small.view.width = 48;
  small.view.height = 36;
  const ray_scene rays(small);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  p.spp = 4;
  p.adaptive_spp = 16;
  const image a = trace_image(small, small.view, rays, nullptr, p);
  p.parallel = false;
  const image b = trace_image(small, small.view, rays, nullptr, p);
  EXPECT_EQ(a.pixels, b.pixels);
  p.seed = 2;
  EXPECT_NE(trace_image(small, small.view, rays, nullptr, p).pixels, a.pixels);
}

TEST(Whitted, AdaptiveSupersamplingRefinesOnlyEdges) {
  scene s = load("assets/whitted/whitted.json");
  s.view.width = 64;
  s.view.height = 48;
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  p.adaptive_spp = 16;
  trace_stats stats;
  trace_image(s, s.view, rays, nullptr, p, nullptr, &stats);
  EXPECT_GT(stats.refined_pixels, 100u);
  EXPECT_LT(stats.refined_pixels, 64u * 48u / 2);
  EXPECT_EQ(stats.primary_rays, 64u * 48u + 16u * stats.refined_pixels);
}

TEST(Whitted, CancelStopsTheTrace) {
  scene s = load("assets/whitted/whitted.json");
  const ray_scene rays(s);
  trace_progress progress;
  progress.cancel = true;
  trace_stats stats;
  trace_image(s, s.view, rays, nullptr, trace_params{}, &progress, &stats);
  EXPECT_TRUE(stats.cancelled);
  EXPECT_EQ(stats.primary_rays, 0u);
}

// ---- two-pass ----

// The furnace (Ke = 1, rho = 0.5) seen at 24 x 24, meshed into `mesh` at 0.5.
scene small_furnace(patch_mesh& mesh) {
  scene s = load("assets/furnace/furnace.json");
  s.view.width = s.view.height = 24;
  std::string error;
  mesher_params mp;
  mp.max_edge = 0.5;
  EXPECT_TRUE(make_patch_mesh(s, mp, mesh, error)) << error;
  return s;
}

TEST(TwoPass, FurnaceStillIsTheExactRadianceEverywhere) {
  // Radiosity pass converged on the furnace: the two-pass still must show
  // Ke / (1 - rho) = 2 in both modes.
  patch_mesh mesh;
  const scene s = small_furnace(mesh);
  ASSERT_GT(mesh.element_count(), 0u);
  auto solver = make_radiosity_solver(s, mesh, radiosity_params{});
  run_solver(*solver, stop_criterion{1e-7, 0, 0});
  const auto solution = make_snapshot(*solver);
  const radiosity_field field(mesh, solution->radiosity, solution->direct);
  const ray_scene rays(s);
  for (diffuse_source mode : {diffuse_source::radiosity, diffuse_source::traced_direct}) {
    trace_params p;
    p.diffuse = mode;
    p.light_samples = 64;
    const image img = trace_image(s, s.view, rays, &field, p);
    // Direct light by 64 shadow rays is noisy near the box's edges (1/d^2).
    const double tolerance = mode == diffuse_source::radiosity ? 1e-3 : 0.15;
    EXPECT_NEAR(mean_radiance(img), 2.0, mode == diffuse_source::radiosity ? 1e-3 : 0.01);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) ASSERT_NEAR(img.at(x, y).g, 2.0, 2.0 * tolerance) << x << "," << y;
  }
}

TEST(TwoPass, AmbientStandsInForTheLightStillUnshot) {
  // The furnace stopped with a third of its power unshot: the solution is
  // dark, and Cohen's ambient term (the unshot power spread evenly and
  // interreflected) is exact for a furnace, so the still that adds it shows
  // Ke / (1 - rho) = 2 again.
  patch_mesh mesh;
  const scene s = small_furnace(mesh);
  ASSERT_GT(mesh.element_count(), 0u);
  auto solver = make_radiosity_solver(s, mesh, radiosity_params{});
  run_solver(*solver, stop_criterion{0.35, 0, 0});
  ASSERT_GT(solver->stats.remaining, 0.1);
  const auto solution = make_snapshot(*solver);
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::radiosity;
  const radiosity_field bare(mesh, solution->radiosity, solution->direct);
  const radiosity_field with_ambient(mesh, solution->radiosity, solution->direct, solution->ambient);
  const double dark = mean_radiance(trace_image(s, s.view, rays, &bare, p));
  const double lit = mean_radiance(trace_image(s, s.view, rays, &with_ambient, p));
  // Measured: 1.648 without the ambient term, 1.998 with it.
  EXPECT_LT(dark, 1.9);
  EXPECT_NEAR(lit, 2.0, 0.02) << "without the ambient term " << dark;
}

TEST(TwoPass, FieldInterpolatesVertexValuesOnExactSpheres) {
  // A sphere inside: the field found from exact hits between the
  // tessellation's vertices matches the vertex values it interpolates.
  scene s;
  const int m = add_material(s, rgb(0.5), rgb(1.0));
  surface ball;
  ball.geometry = sphere{vec3(0.0), 1.0, m};
  s.surfaces.push_back(ball);
  patch_mesh mesh;
  std::string error;
  mesher_params mp;
  mp.max_edge = 0.3;
  ASSERT_TRUE(make_patch_mesh(s, mp, mesh, error)) << error;
  std::vector<rgb> radiosity(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    radiosity[v] = mesh.vertex_emission[v] + rgb(mesh.positions[v].y + 2.0);  // reflected = y + 2
  const radiosity_field field(mesh, radiosity, {});
  for (int i = 0; i < 200; ++i) {
    const double phi = i * 2.399963, y = 1 - 2 * (i + 0.5) / 200, r = std::sqrt(1 - y * y);
    const vec3 p(r * std::cos(phi), y, r * std::sin(phi));
    const diffuse_radiosity b = field.at(0, p, p);
    EXPECT_NEAR(b.reflected.r, y + 2.0, 0.02) << i;  // linear in y up to the chord's sag
    EXPECT_EQ(b.indirect, b.reflected);
  }
  EXPECT_EQ(field.at(5, vec3(0.0), vec3(0, 1, 0)).reflected, rgb(0.0));  // no such surface
}

TEST(TwoPass, FieldOnAFloorIsExactInsideAndTheNearestEdgeOutside) {
  // The inside of a closed box: on its floor the probe along the normal
  // finds the element under the point (a wall meets the floor at every
  // edge, and its elements must not be taken), and a point past the
  // floor's edge takes the edge's value from the nearest element.
  scene s;
  add_closed_box(s, vec3(0.0), vec3(1.0), add_material(s, rgb(0.5)));
  const patch_mesh mesh = mesh_of(s, 0.2);
  std::vector<rgb> radiosity(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    radiosity[v] = rgb(mesh.positions[v].x + 2.0 * mesh.positions[v].z + 10.0 * mesh.positions[v].y);
  const radiosity_field field(mesh, radiosity, {});
  const int floor = 4;  // {4, 5, 1, 0}: y = 0, facing up
  const vec3 up(0, 1, 0);
  random_stream rng(3, 0, 0);
  for (int i = 0; i < 500; ++i) {
    const vec3 p(rng.uniform(), 0.0, rng.uniform());
    EXPECT_NEAR(field.at(floor, p, up).reflected.r, p.x + 2.0 * p.z, 1e-6) << i;
    EXPECT_NEAR(field.at(floor, p, -up).reflected.r, p.x + 2.0 * p.z, 1e-6) << i;  // either way round
  }
  EXPECT_NEAR(field.at(floor, vec3(1.05, 0.0, 0.5), up).reflected.r, 2.0, 1e-6);  // past x = 1: the edge's value
  EXPECT_NEAR(field.at(floor, vec3(0.3, 0.01, 0.0), up).reflected.r, 0.3, 1e-6);  // just above the edge at z = 0
}

// ---- path tracer ----

// The white furnace, path traced at a small size.
image furnace_path(int size, int spp, std::uint64_t seed) {
  scene s = load("assets/furnace/furnace.json");
  s.view.width = s.view.height = size;
  const ray_scene rays(s);
  trace_params p;
  p.method = integrator::path;
  p.spp = spp;
  p.seed = seed;
  return trace_image(s, s.view, rays, nullptr, p);
}

TEST(PathTracer, FurnaceConvergesToEOverOneMinusRho) {
  // Ke = 1, rho = 0.5: every pixel's radiance is 2.
  const image exact = uniform_image(16, 16, rgb(2.0));
  const double e16 = relative_rmse(furnace_path(16, 16, 1), exact);
  const double e64 = relative_rmse(furnace_path(16, 64, 1), exact);
  const double e256 = relative_rmse(furnace_path(16, 256, 1), exact);
  const image converged = furnace_path(16, 2048, 1);
  const double e2048 = relative_rmse(converged, exact);
  // 1/sqrt(spp): a factor 2 per 4x samples (measured 2.02, 1.96, ...).
  EXPECT_NEAR(e16 / e64, 2.0, 0.4);
  EXPECT_NEAR(e64 / e256, 2.0, 0.4);
  // Per pixel within 1% at 2048 samples; unbiased: the mean within 0.2%.
  EXPECT_LT(e2048, 0.01);
  EXPECT_NEAR(mean_radiance(converged), 2.0, 2.0 * 0.002);
}

TEST(PathTracer, PointLightOnADiffusePlaneMatchesWhitted) {
  // Direct light only (the floor is all there is): both tracers agree.
  const scene s = lit_floor(0.6, rgb(10.0), 2.0);
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  const image whitted = trace_image(s, s.view, rays, nullptr, p);
  p.method = integrator::path;
  const image path = trace_image(s, s.view, rays, nullptr, p);
  EXPECT_LT(relative_rmse(path, whitted), 1e-9);
}

}  // namespace
}  // namespace bounce
