// The bench's measures: picture and per-vertex errors, the closed forms it
// measures against, the Pareto front, growth fits, and short runs.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "image/image_metrics.h"
#include "measure/bench.h"
#include "measure/closed_forms.h"
#include "mesh_builders.h"
#include "scene/scene_io.h"

namespace bounce {
namespace {

using std::numbers::pi;

scene bench_scene(const std::string& name) {
  scene s;
  load_report report;
  EXPECT_TRUE(load_scene("embedded:bench/" + name, s, report)) << report.error;
  return s;
}

using test_support::mesh_of;

// ---- metrics ----

TEST(ImageMetrics, KnownDifferencesGiveKnownErrors) {
  const image a = uniform_image(8, 8, rgb(1.0));
  EXPECT_EQ(relative_rmse(a, a), 0.0);
  EXPECT_EQ(max_relative_error(a, a), 0.0);
  const image b = uniform_image(8, 8, rgb(1.1));
  EXPECT_NEAR(relative_rmse(b, a), 0.1, 1e-6);
  EXPECT_NEAR(mean_relative_error(b, a), 0.1, 1e-6);
  image c = a;
  c.pixels[0] = 3.0f;  // one channel of one pixel off by 2
  EXPECT_NEAR(relative_rmse(c, a), std::sqrt(4.0 / 192.0), 1e-6);
  EXPECT_NEAR(max_relative_error(c, a), 2.0, 1e-6);
  EXPECT_EQ(relative_rmse(a, uniform_image(4, 4, rgb(1.0))), INFINITY);  // sizes differ
}

TEST(ImageMetrics, DownsampleAveragesAndExclusionSkipsPixels) {
  image a = uniform_image(4, 4, rgb(1.0));
  a.pixels[0] = 5.0f;
  const image d = downsample(a, 2);
  ASSERT_EQ(d.width, 2);
  EXPECT_NEAR(d.at(0, 0).r, 2.0, 1e-6);
  EXPECT_NEAR(d.at(1, 1).r, 1.0, 1e-6);
  const std::vector<bool> bright = bright_pixels(a, 2.0);
  EXPECT_TRUE(bright[0]);
  EXPECT_FALSE(bright[1]);
  image masked = a;
  exclude_pixels(masked, bright, 1);
  EXPECT_TRUE(std::isnan(masked.at(1, 1).r));
  EXPECT_FALSE(std::isnan(masked.at(2, 2).r));
  EXPECT_NEAR(mean_radiance(masked), 1.0, 1e-6);
  EXPECT_EQ(relative_rmse(masked, uniform_image(4, 4, rgb(1.0))), 0.0);
  EXPECT_TRUE(std::isnan(downsample(masked, 2).at(0, 0).r));
}

TEST(ImageMetrics, ContrastEdgesFindAStep) {
  image a = uniform_image(6, 1, rgb(1.0));
  for (int x = 3; x < 6; ++x)
    for (int c = 0; c < 3; ++c) a.pixels[3 * x + c] = 2.0f;
  const std::vector<bool> edges = contrast_edges(a, 0.1);
  EXPECT_EQ(edges, (std::vector<bool>{false, false, true, true, false, false}));
}

TEST(VertexMetrics, IdenticalIsZeroAndKnownOffsetsGiveKnownErrors) {
  const std::vector<rgb> exact(10, rgb(2.0));
  EXPECT_EQ(vertex_relative_error(exact, exact).rmse, 0.0);
  EXPECT_EQ(vertex_relative_error(exact, exact).max, 0.0);
  std::vector<rgb> test(10, rgb(2.2));
  EXPECT_NEAR(vertex_relative_error(test, exact).rmse, 0.1, 1e-12);
  EXPECT_NEAR(vertex_relative_error(test, exact).max, 0.1, 1e-12);
  test = exact;
  test[3].g = 4.0;  // one value of 30 off by 2: RMS sqrt(4 / 30), relative to the mean 2
  EXPECT_NEAR(vertex_relative_error(test, exact).rmse, std::sqrt(4.0 / 30.0) / 2.0, 1e-12);
  EXPECT_NEAR(vertex_relative_error(test, exact).max, 1.0, 1e-12);
}

TEST(ParetoFront, KeepsOnlyPointsNothingBeatsOnBothCounts) {
  const std::vector<double> t = {1, 2, 3, 2, 4, 5, 1};
  const std::vector<double> e = {0.5, 0.2, 0.1, 0.3, 0.1, NAN, 0.5};
  // (2, 0.3) loses to (2, 0.2); (4, 0.1) to (3, 0.1); NaN errors never count;
  // two equal points do not beat each other.
  EXPECT_EQ(pareto_front(t, e), (std::vector<bool>{true, true, true, false, false, false, true}));
}

TEST(GrowthExponent, FitsAPowerLaw) {
  const std::vector<double> n = {2e3, 1e4, 5e4, 2e5};
  std::vector<double> y;
  for (double x : n) y.push_back(3e-6 * std::pow(x, 1.5));
  EXPECT_NEAR(growth_exponent(n, y), 1.5, 1e-12);
  y[3] = NAN;  // a size that was not measured is left out
  EXPECT_NEAR(growth_exponent(n, y), 1.5, 1e-12);
}

TEST(TimeToError, InterpolatesInLogLogBetweenStops) {
  bench_curve c;
  c.points = {{.seconds = 1, .error = 0.1}, {.seconds = 10, .error = 0.01}};
  EXPECT_NEAR(time_to_error(c, 0.1), 1.0, 1e-12);
  EXPECT_NEAR(time_to_error(c, std::sqrt(0.1 * 0.01)), std::sqrt(10.0), 1e-9);
  EXPECT_TRUE(std::isnan(time_to_error(c, 0.001)));
}

TEST(ClosedForms, MatchTheReferenceFigures) {
  EXPECT_NEAR(4 * corner_point_rectangle(0.5, 0.5, 1), 0.239456, 1e-6);
  EXPECT_NEAR(parallel_rectangles(1, 1, 1), 0.199825, 1e-6);
  EXPECT_NEAR(perpendicular_rectangles(1, 1, 1), 0.200044, 1e-6);
  EXPECT_NEAR(perpendicular_rectangles(1, 2, 0.5), 0.078650, 1e-6);
  EXPECT_NEAR(coaxial_discs(1, 1, 1), 0.381966, 1e-6);
}

// The two closed forms of the squares scenes agree: the per-vertex one
// (Lambert's formula at every point) integrated over a fine mesh gives the
// area-to-area one (items 2 and 3).
TEST(BenchExact, SquaresPerVertexIntegratesToTheAreaFormFactor) {
  for (const char* name : {"squares_perpendicular.json", "squares_parallel.json"}) {
    const scene s = bench_scene(name);
    const patch_mesh mesh = mesh_of(s, 0.02);
    const rgb exact = exact_reflected_power(exact_kind::emitter_receiver, s, mesh);
    const double f = std::string(name) == "squares_parallel.json" ? 0.199825 : 0.200044;
    EXPECT_NEAR(exact.r, 0.5 * pi * f, 1e-6) << name;  // rho E A F, E = pi x ke
    const rgb integrated = reflected_power(mesh, exact_vertex_radiosity(exact_kind::emitter_receiver, s, mesh));
    EXPECT_NEAR(integrated.r / exact.r, 1.0, 2e-3) << name;
  }
}

TEST(BenchExact, FurnaceAndSphereClosedForms) {
  const scene furnace = bench_scene("furnace.json");
  const patch_mesh mesh = mesh_of(furnace, 0.5);
  for (const rgb& b : exact_vertex_radiosity(exact_kind::furnace, furnace, mesh)) EXPECT_NEAR(b.g, 2 * pi, 1e-12);
  // Reflected power: the area (24) x (B - E) = 24 pi.
  EXPECT_NEAR(exact_reflected_power(exact_kind::furnace, furnace, mesh).g, 24 * pi, 1e-9);
  const scene sphere = bench_scene("sphere.json");
  const patch_mesh sm = mesh_of(sphere, 0.5);
  // The upper half emits (E = pi): B - E = rho P_E / ((1 - rho) A) = 1.5 pi A_upper / A, about 0.75 pi.
  double upper = 0.0;
  for (std::size_t e = 0; e < sm.element_count(); ++e)
    if (sm.vertex_emission[sm.elements[e][0]].r > 0) upper += sm.element_areas[e];
  const std::vector<rgb> b = exact_vertex_radiosity(exact_kind::sphere_interior, sphere, sm);
  for (std::size_t v = 0; v < sm.vertex_count(); ++v)
    EXPECT_NEAR(b[v].r - sm.vertex_emission[v].r, 1.5 * pi * upper / total_area(sm), 1e-9);
  EXPECT_NEAR(upper / total_area(sm), 0.5, 0.01);
}

TEST(BenchRun, ProgressiveFurnaceErrorFallsAlongOneRun) {
  const scene s = bench_scene("furnace.json");
  bench_setting setting;
  setting.solver.method = solver_method::progressive;  // not the default
  setting.solver.max_edge = 0.5;
  setting.solver.patch_edge = 0.0;
  setting.solver.stop.remaining = 1e-4;
  bench_truth truth;
  truth.exact = exact_kind::furnace;
  const bench_result r = run_bench(s, setting, truth);
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.curves.size(), 1u);
  EXPECT_EQ(r.curves[0].method, "raycast");
  EXPECT_EQ(r.links, 0u);
  const auto& points = r.curves[0].points;
  ASSERT_GE(points.size(), 5u);
  for (std::size_t i = 1; i < points.size(); ++i) {
    EXPECT_GT(points[i].seconds, points[i - 1].seconds);
    EXPECT_GE(points[i].steps, points[i - 1].steps);
    EXPECT_LE(points[i].error, points[i - 1].error * 1.0001);  // shooting only adds light it owes
  }
  EXPECT_GT(points.front().error, 0.3);
  EXPECT_LT(points.back().error, 1e-3);
  EXPECT_LT(points.back().balance_error, 1e-12);
  EXPECT_GT(r.first_picture_seconds, 0.0);
}

// The default solver: the bench runs the hierarchical solver through the
// same state, names its curve for it, and reports its links at the end.
TEST(BenchRun, HierarchicalFurnaceConvergesAndReportsItsLinks) {
  const scene s = bench_scene("furnace_099.json");
  bench_setting setting;
  ASSERT_EQ(setting.solver.method, solver_method::hierarchical);
  setting.solver.max_edge = 0.5;
  setting.solver.stop.remaining = 1e-6;
  bench_truth truth;
  truth.exact = exact_kind::furnace;
  const bench_result r = run_bench(s, setting, truth);
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.curves.size(), 1u);
  EXPECT_EQ(r.curves[0].method, "hierarchical");
  const auto& points = r.curves[0].points;
  ASSERT_GE(points.size(), 2u);
  EXPECT_GT(points.front().error, 0.3);  // B = 100 E: the first step's direct light is far from it
  EXPECT_LT(points.back().error, 1e-4);
  EXPECT_LE(points.back().remaining, 1e-6);
  EXPECT_TRUE(std::isnan(points.back().balance_error));  // no shooting balance to report
  for (std::size_t i = 1; i < points.size(); ++i) EXPECT_GT(points[i].steps, points[i - 1].steps);
  EXPECT_GT(r.links, 0u);
  EXPECT_TRUE(r.links_final);
  EXPECT_DOUBLE_EQ(r.link_tolerance, setting.solver.link_tolerance);
  EXPECT_GT(r.first_picture_seconds, 0.0);
  EXPECT_LE(r.first_picture_seconds, points.front().seconds);
}

TEST(BenchRun, ReferenceSolversAreExactOnTheFurnace) {
  const scene s = bench_scene("furnace_099.json");
  bench_setting setting;
  setting.kind = bench_solver::reference;
  setting.solver.max_edge = 0.5;
  setting.solver.patch_edge = 0.0;
  bench_truth truth;
  truth.exact = exact_kind::furnace;
  const bench_result r = run_bench(s, setting, truth);
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.curves.size(), 2u);
  EXPECT_EQ(r.curves[0].method, "reference-lu");
  EXPECT_EQ(r.curves[1].method, "gauss-seidel");
  EXPECT_LT(r.curves[0].points[0].error, 1e-9);  // B = 100 E: the hard, slowly converging case
  EXPECT_LT(r.curves[1].points[0].error, 1e-9);
}

TEST(BenchRun, PathTracerErrorHalvesPerFourTimesTheSamples) {
  scene s = bench_scene("squares_parallel.json");
  s.view.width = s.view.height = 16;
  bench_truth truth;
  truth.picture = path_reference(s, 2048, 1);
  truth.exclude_above = 0.5;
  truth.downsample = 1;
  bench_setting setting;
  setting.kind = bench_solver::path_tracer;
  setting.path_max_spp = 64;
  setting.solver.stop.seconds = 100.0;
  const bench_result r = run_bench(s, setting, truth);
  ASSERT_EQ(r.curves.size(), 1u);
  const auto& p = r.curves[0].points;
  ASSERT_EQ(p.size(), 7u);  // 1, 2, ..., 64 spp
  // Noise falls as 1 / sqrt(spp): from 4 to 64 spp (1 spp is the pixel
  // centre, not a random sample), 4x less error, loosely.
  EXPECT_GT(p[2].error / p[6].error, 2.5);
  EXPECT_LT(p[2].error / p[6].error, 6.5);
}

}  // namespace
}  // namespace bounce
